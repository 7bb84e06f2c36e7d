// optical_model.hpp - the settings both ray casters share and what they
// derive from them: the parameters (sample distance, labels and gradients
// per sample, shading, boundary emphasis, early termination, jitter, the
// coarse pass) and the shading constants, so the CPU and OpenGL ray
// casters render one model.
#pragma once

#include <arbor/renderer.h>
#include <arbor/sdk/params.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace arbor::raycast {

// Pixels per coarse ray (along each side): 4 until timings say otherwise,
// then one of 2, 2.5, ... 8.
constexpr double kCoarseStart = 4, kCoarseMin = 2, kCoarseMax = 8, kCoarseStepBy = 0.5;
constexpr double kCoarseStep = 2.0; // the coarse pass samples at this many times the full step
// A step in a cell where structures meet (labels per sample) is taken as
// this many samples, so a structure thinner than a step is not missed
// between samples (the GLSL ray caster's four).
constexpr int kRefine = 4;

// The parameters of the optical model and the coarse pass, in the order
// the renderers list them.
std::vector<sdk::ParamSpec> optical_model_params();

struct Shading {
    bool enabled = true;
    float ambient = 0.3f, diffuse = 0.7f;
    // specular * ndl^shininess for ndl = i / 256: no pow() per sample.
    std::array<float, 258> highlight{};

    void tabulate(float specular, float shininess)
    {
        for (std::size_t i = 0; i < highlight.size(); ++i)
            highlight[i] = specular * std::pow(std::min(1.0f, i / 256.0f), shininess);
    }
    // From the parameters optical_model_params() declares.
    static Shading from(const sdk::ParamSet &params);
};

// How many pixels share a coarse ray: fixed, or chosen to reach a frame
// rate from the time whole coarse frames took (smoothed, so one slow frame
// does not make the picture jump).  It changes only at a call whose region
// starts at (0, 0), the first tile of a frame, so a frame's tiles agree.
class CoarseRate {
public:
    // Pixels per ray for this call; `fixed` > 0 fixes it.
    double pixels_for(const arbor_render_request_v2 &request, double frames_per_second, double fixed);
    // A coarse call for a region of this many pixels took `seconds`.
    void rendered(double seconds, double pixels);

private:
    void adapt(double seconds, double budget);

    double pixels_ = kCoarseStart;
    double seconds_ = 0.0;                         // smoothed time of a whole coarse frame
    double frame_seconds_ = 0, frame_pixels_ = 0;  // the coarse frame being rendered, tile by tile
};

} // namespace arbor::raycast
