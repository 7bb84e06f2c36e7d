// gl_scene.hpp - the scene the OpenGL ray caster's tests render through
// it and through the CPU ray caster: a labelled ball in a shell (with the
// labels' tree, so samples resolve their labels), three ramp functions, a
// perspective camera (test_renderer_gl*.cpp).
#pragma once

#include "plugin_fixture.hpp"
#include "image_psnr.hpp"

#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <cmath>

namespace arbor::test::gl_scene {

constexpr int64_t kN = 64;
constexpr uint32_t kLut = 256;
constexpr const char *kGl = "org.arbor.renderer.gl-raycast", *kCpu = "org.arbor.renderer.cpu-raycast";

// Anisotropic, as scans are; {1, 1, 3}: thick slices.
inline Volume ball_in_shell(const std::array<double, 3> &spacing = {1.0, 0.9, 1.3})
{
    Geometry g;
    g.dims = {kN, kN, kN};
    g.spacing = spacing;
    g.origin = {-20, 10, 5};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t j = 0; j < kN; ++j)
            for (int64_t i = 0; i < kN; ++i) {
                const double r = std::hypot(i - 31.5, j - 29.0, k - 33.0);
                // A ramp inside the ball, so values between the steps are sampled too.
                v.as<float>()[i + kN * (j + kN * k)] =
                    static_cast<float>(r < 12 ? 70 + 2.5 * (12 - r) : r > 22 && r < 26 ? 80 : 10 + 0.2 * i);
            }
    return v;
}

// Over [0, 100]: a ramp of opacity from 45 up, colour `rgb`.
inline void ramp_function(TransferFunctions &tf, uint32_t b, std::array<float, 3> rgb, float alpha)
{
    std::vector<float> lut(kLut * 4);
    for (uint32_t i = 0; i < kLut; ++i) {
        const double value = 100.0 * i / (kLut - 1);
        for (int c = 0; c < 3; ++c)
            lut[4 * i + c] = rgb[c] * static_cast<float>(0.6 + 0.4 * value / 100.0);
        lut[4 * i + 3] = value >= 45.0 ? alpha * static_cast<float>(std::min(1.0, (value - 45.0) / 30.0)) : 0.0f;
    }
    tf.assign(b, {0.0, 100.0}, lut.data());
}

struct Pair {
    Volume volume;
    std::vector<uint32_t> labels = std::vector<uint32_t>(kN * kN * kN, 0);
    // How the labels nest: samples in mixed cells resolve their labels.
    std::vector<int32_t> parent{-1, 0, 0};
    std::vector<double> saddle{0.0, 40.0, 60.0};
    TransferFunctions tf{3, kLut, 1.0};
    PluginInstance gl = test::built_plugins().create(kGl);
    PluginInstance cpu = test::built_plugins().create(kCpu);
    arbor_camera camera{};
    arbor_volume view = volume.view();
    arbor_label_map map{};
    arbor_render_request request{};
    uint64_t tf_revision = 1;

    explicit Pair(const std::array<double, 3> &spacing = {1.0, 0.9, 1.3}) : volume(ball_in_shell(spacing))
    {
        for (int64_t k = 0; k < kN; ++k)
            for (int64_t j = 0; j < kN; ++j)
                for (int64_t i = 0; i < kN; ++i) {
                    const double r = std::hypot(i - 31.5, j - 29.0, k - 33.0);
                    labels[static_cast<std::size_t>(i + kN * (j + kN * k))] = r < 17 ? (i < 32 ? 1u : 2u) : 0u;
                }
        ramp_function(tf, 0, {0.9f, 0.8f, 0.6f}, 0.12f);
        ramp_function(tf, 1, {0.8f, 0.2f, 0.2f}, 0.5f);
        ramp_function(tf, 2, {0.2f, 0.4f, 0.9f}, 0.5f);
        camera.struct_size = sizeof camera;
        camera.projection = ARBOR_PROJECTION_PERSPECTIVE;
        camera.view_angle = 30;
        const double c[3] = {-20 + spacing[0] * 31.5, 10 + spacing[1] * 31.5, 5 + spacing[2] * 31.5};
        camera.position[0] = c[0] + 70, camera.position[1] = c[1] - 100, camera.position[2] = c[2] + 50;
        for (int a = 0; a < 3; ++a)
            camera.focal_point[a] = c[a];
        camera.view_up[2] = 1;
        map.struct_size = sizeof map;
        map.label_count = 3;
        map.dims[0] = map.dims[1] = map.dims[2] = kN;
        map.labels = labels.data();
        map.parent = parent.data();
        map.saddle_value = saddle.data();
        request.struct_size = sizeof request;
        request.volume = &view;
        request.labels = &map;
        request.transfer_functions = &tf.record();
        request.camera = &camera;
        request.volume_revision = request.labels_revision = 3;
        set("coarse-pixels", "4");
    }
    void set(const std::string &param, const std::string &text)
    {
        for (PluginInstance *r : {&gl, &cpu})
            r->set_param(param, parse_param_value(*r->find_param(param), text).value);
    }
    RenderedImage render(PluginInstance &r, FramePass pass = {}, uint32_t w = 160, uint32_t h = 128)
    {
        pass.transfer_functions_revision = tf_revision;
        return render_image(r, request, w, h, nullptr, {}, pass);
    }
    // PSNR of the GL image against the CPU's, this pass.
    double agreement(FramePass pass = {}, uint32_t w = 160, uint32_t h = 128)
    {
        const RenderedImage a = render(gl, pass, w, h), b = render(cpu, pass, w, h);
        return test::psnr(a, b);
    }
};

} // namespace arbor::test::gl_scene
