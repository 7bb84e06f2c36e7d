// global_ramp.hpp - one global transfer function for renderer comparisons:
// clear below 15% of [lo, hi], then an opacity ramp to 0.6 with heat colours.
#pragma once

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

} // namespace arbor::test
