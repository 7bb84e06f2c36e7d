#include "label_colors.hpp"

#include <cmath>

namespace arbor::io {

Rgb8 label_color(uint32_t label)
{
    if (label == 0)
        return {64, 64, 64};
    const double hue = std::fmod(137.50776405 * label, 360.0) / 60.0;
    const double value = (label % 2) ? 0.95 : 0.8;
    const double saturation = (label % 3 == 2) ? 0.55 : 0.8;
    const double c = value * saturation;
    const double x = c * (1.0 - std::fabs(std::fmod(hue, 2.0) - 1.0));
    double r = 0, g = 0, b = 0;
    switch (static_cast<int>(hue)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
    }
    const double m = value - c;
    const auto byte = [m](double v) { return static_cast<uint8_t>(std::lround(255.0 * (v + m))); };
    return {byte(r), byte(g), byte(b)};
}

} // namespace arbor::io
