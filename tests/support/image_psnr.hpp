// image_psnr.hpp - peak signal-to-noise ratio of two rendered images of the
// same size, over RGB (both composited over the same background), in dB;
// +infinity when they are equal.  The renderer comparisons' measure.
#pragma once

#include "core/rendered_image.hpp"

#include <cmath>
#include <cstddef>

namespace arbor::test {

// Mean squared error over RGB, per channel value.
inline double mean_squared_error(const RenderedImage &a, const RenderedImage &b)
{
    double se = 0;
    const std::size_t pixels = std::size_t{a.width} * a.height;
    for (std::size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) {
            const double d = a.rgba[4 * p + c] - b.rgba[4 * p + c];
            se += d * d;
        }
    return se / (3.0 * static_cast<double>(pixels));
}

inline double psnr_of_mse(double mse)
{
    return mse > 0 ? 10.0 * std::log10(1.0 / mse) : INFINITY;
}

inline double psnr(const RenderedImage &a, const RenderedImage &b)
{
    return psnr_of_mse(mean_squared_error(a, b));
}

} // namespace arbor::test
