#include "colour_space.hpp"

#include <algorithm>
#include <cmath>

namespace arbor {

namespace {

// sRGB primaries and the D65 white (IEC 61966-2-1).
constexpr double kToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                 {0.2126729, 0.7151522, 0.0721750},
                                 {0.0193339, 0.1191920, 0.9503041}};
constexpr double kToRgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                 {-0.9692660, 1.8760108, 0.0415560},
                                 {0.0556434, -0.2040259, 1.0572252}};
constexpr double kWhite[3] = {0.95047, 1.0, 1.08883};

double to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double to_encoded(double c)
{
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double lab_f(double t)
{
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

double lab_f_inverse(double t)
{
    constexpr double d = 6.0 / 29.0;
    return t > d ? t * t * t : 3 * d * d * (t - 4.0 / 29.0);
}

} // namespace

std::array<double, 3> rgb_to_hsv(const Rgb &c)
{
    const double hi = std::max({c[0], c[1], c[2]}), lo = std::min({c[0], c[1], c[2]}), span = hi - lo;
    double hue = 0.0;
    if (span > 0) {
        if (hi == c[0])
            hue = 60.0 * std::fmod((c[1] - c[2]) / span, 6.0);
        else if (hi == c[1])
            hue = 60.0 * ((c[2] - c[0]) / span + 2.0);
        else
            hue = 60.0 * ((c[0] - c[1]) / span + 4.0);
        if (hue < 0)
            hue += 360.0;
    }
    return {hue, hi > 0 ? span / hi : 0.0, hi};
}

Rgb hsv_to_rgb(const std::array<double, 3> &hsv)
{
    const double h = std::fmod(std::fmod(hsv[0], 360.0) + 360.0, 360.0) / 60.0;
    const double s = hsv[1], v = hsv[2];
    const double chroma = v * s, x = chroma * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m = v - chroma;
    Rgb c{};
    switch (static_cast<int>(h)) {
    case 0: c = {chroma, x, 0}; break;
    case 1: c = {x, chroma, 0}; break;
    case 2: c = {0, chroma, x}; break;
    case 3: c = {0, x, chroma}; break;
    case 4: c = {x, 0, chroma}; break;
    default: c = {chroma, 0, x}; break;
    }
    return {c[0] + m, c[1] + m, c[2] + m};
}

Lab rgb_to_lab(const Rgb &c)
{
    const double lin[3] = {to_linear(c[0]), to_linear(c[1]), to_linear(c[2])};
    double f[3];
    for (int i = 0; i < 3; ++i)
        f[i] = lab_f((kToXyz[i][0] * lin[0] + kToXyz[i][1] * lin[1] + kToXyz[i][2] * lin[2]) / kWhite[i]);
    return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
}

Rgb lab_to_rgb(const Lab &c)
{
    const double fy = (c[0] + 16) / 116, fx = fy + c[1] / 500, fz = fy - c[2] / 200;
    const double xyz[3] = {kWhite[0] * lab_f_inverse(fx), kWhite[1] * lab_f_inverse(fy), kWhite[2] * lab_f_inverse(fz)};
    Rgb out{};
    for (int i = 0; i < 3; ++i) {
        const double lin = kToRgb[i][0] * xyz[0] + kToRgb[i][1] * xyz[1] + kToRgb[i][2] * xyz[2];
        out[i] = lin < 0 ? -to_encoded(-lin) : to_encoded(lin);
    }
    return out;
}

} // namespace arbor
