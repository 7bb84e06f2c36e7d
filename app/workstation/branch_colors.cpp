#include "branch_colors.hpp"

#include "io/label_colors.hpp"

#include <algorithm>

namespace arbor::workstation {

std::vector<std::array<float, 3>> branch_colors(const TransferFunctions &tf)
{
    std::vector<std::array<float, 3>> out(tf.branch_count());
    for (uint32_t b = 0; b < tf.branch_count(); ++b) {
        const float *lut = tf.lut(b);
        double sum[3] = {0, 0, 0}, weight = 0;
        for (uint32_t i = 0; i < tf.lut_size(); ++i) {
            const double a = lut[4 * i + 3];
            for (int k = 0; k < 3; ++k)
                sum[k] += a * lut[4 * i + k];
            weight += a;
        }
        if (weight > 1e-9) {
            for (int k = 0; k < 3; ++k)
                out[b][k] = static_cast<float>(sum[k] / weight);
        } else {
            const io::Rgb8 c = io::label_color(b);
            for (int k = 0; k < 3; ++k)
                out[b][k] = c[k] / 255.0f;
        }
    }
    return out;
}

std::vector<std::array<float, 3>> overlay_colors(const std::vector<std::array<float, 3>> &colors)
{
    std::vector<std::array<float, 3>> out(colors.size());
    for (std::size_t b = 0; b < colors.size(); ++b) {
        std::array<float, 3> c = colors[b];
        float hi = std::max({c[0], c[1], c[2]}), lo = std::min({c[0], c[1], c[2]});
        if (hi - lo < 0.04f) { // grey: no hue of its own
            const io::Rgb8 l = io::label_color(static_cast<uint32_t>(b));
            c = {l[0] / 255.0f, l[1] / 255.0f, l[2] / 255.0f};
            hi = std::max({c[0], c[1], c[2]});
            lo = std::min({c[0], c[1], c[2]});
        }
        // HSV with the hue kept: value and saturation raised.
        const float v = std::max(hi, 0.9f);
        const float sat = std::max(hi > 0 ? (hi - lo) / hi : 0.0f, 0.65f);
        for (int k = 0; k < 3; ++k) {
            const float t = hi > lo ? (c[k] - lo) / (hi - lo) : 0.0f; // 0 at the smallest component, 1 at the largest
            out[b][k] = v * (1 - sat * (1 - t));
        }
    }
    return out;
}

} // namespace arbor::workstation
