// colour_space.hpp - the conversions the host needs to apply a depiction's
// hue and vividness to transfer functions (depictor.h): straight,
// display-encoded sRGB to and from HSV and CIELAB (D65).
#pragma once

#include <array>

namespace arbor {

using Rgb = std::array<double, 3>; // straight sRGB, each in [0, 1] when in gamut
using Lab = std::array<double, 3>; // L* in [0, 100], a*, b*

// Hexcone HSV: hue in degrees [0, 360), saturation and value in [0, 1].
std::array<double, 3> rgb_to_hsv(const Rgb &c);
Rgb hsv_to_rgb(const std::array<double, 3> &hsv);

// CIELAB of the D65 white point, through linear sRGB (IEC 61966-2-1).
Lab rgb_to_lab(const Rgb &c);
// Not clamped: out-of-gamut colours give components outside [0, 1].
Rgb lab_to_rgb(const Lab &c);

} // namespace arbor
