#include "branch_colors.hpp"

#include "io/label_colors.hpp"

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

} // namespace arbor::workstation
