// global_ramp.hpp - the scene of the renderer comparisons (CPU vs VTK): one
// global transfer function, clear below 15% of [lo, hi], then an opacity ramp
// to 0.6 with heat colours; a request over an opaque black background; and
// shading switched on or off on both renderers alike.
#pragma once

#include "core/volume_statistics.hpp"
#include "host/param_text.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <algorithm>
#include <vector>

namespace arbor::test {

inline void global_ramp(TransferFunctions &tf, double lo, double hi)
{
    std::vector<float> lut(std::size_t{tf.lut_size()} * 4);
    for (uint32_t i = 0; i < tf.lut_size(); ++i) {
        const double u = i / (tf.lut_size() - 1.0);
        lut[4 * i + 0] = static_cast<float>(std::min(1.0, 2.5 * u));
        lut[4 * i + 1] = static_cast<float>(std::clamp(2.5 * u - 0.8, 0.0, 1.0));
        lut[4 * i + 2] = static_cast<float>(std::clamp(3.0 * u - 2.0, 0.0, 1.0));
        lut[4 * i + 3] = static_cast<float>(u < 0.15 ? 0.0 : 0.6 * (u - 0.15) / 0.85);
    }
    tf.assign(0, {lo, hi}, lut.data());
}

inline arbor_render_request global_request(const arbor_volume &volume, const TransferFunctions &tf,
                                           const arbor_camera &camera)
{
    arbor_render_request r{};
    r.struct_size = sizeof r;
    r.volume = &volume;
    r.transfer_functions = &tf.record();
    r.camera = &camera;
    r.background[3] = 1.0f;
    r.volume_revision = 1;
    return r;
}

// The renderer benchmarks' scene of a volume: the global ramp over its value
// range (opacity unit distance 4 voxels), seen from azimuth 30, elevation 20.
struct RampScene {
    explicit RampScene(const Volume &v)
        : view(v.view()),
          tf(1, 256, 4.0 * std::min({v.geometry().spacing[0], v.geometry().spacing[1], v.geometry().spacing[2]}))
    {
        const VolumeStatistics stats = compute_statistics(v);
        global_ramp(tf, stats.min, stats.max);
        Orbit orbit;
        orbit.azimuth = 30;
        orbit.elevation = 20;
        camera = orbit_camera(v.geometry(), orbit);
        request = global_request(view, tf, camera);
    }
    RampScene(const RampScene &) = delete;
    RampScene &operator=(const RampScene &) = delete;

    arbor_volume view;
    TransferFunctions tf;
    arbor_camera camera{};
    arbor_render_request request{}; // points at the members above
};

inline void set_shading(PluginInstance &renderer, bool on)
{
    renderer.set_param("shading", parse_param_value(*renderer.find_param("shading"), on ? "true" : "false").value);
}

// Plain emission and absorption, as VTK's ray caster does it: no opacity
// scaled by the gradient (the CPU ray caster's boundary emphasis).
inline void plain_opacity(PluginInstance &renderer)
{
    if (const arbor_param_desc *d = renderer.find_param("boundary-emphasis"))
        renderer.set_param("boundary-emphasis", parse_param_value(*d, "0").value);
}

} // namespace arbor::test
