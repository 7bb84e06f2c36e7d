// colour_space.cpp - HSV, sRGB and CIELAB conversions from their defining
// formulas (IEC 61966-2-1, CIE 15), and the lightness/vividness search of
// colour_for() used to build perceptually ordered transfer functions.
#include "colour_space.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace arbor::tf {

namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

constexpr double kWhiteX = 0.95047;
constexpr double kWhiteY = 1.0;
constexpr double kWhiteZ = 1.08883;

// Linear sRGB (D65) to XYZ, the matrix derived from the sRGB primaries and
// white point, published at 7 digits.  Rounded, its Y row sums to 1.0000001,
// which leaves greys with a* ~ -2e-5; each row is rescaled (by at most 1e-7)
// so that sRGB white maps exactly onto the reference white and greys are
// exactly achromatic.
constexpr Matrix3 kPublishedRgbToXyz = {{
    {0.4124564, 0.3575761, 0.1804375},
    {0.2126729, 0.7151522, 0.0721750},
    {0.0193339, 0.1191920, 0.9503041},
}};

constexpr Matrix3 onto_white(const Matrix3 &m, const std::array<double, 3> &white)
{
    Matrix3 out = m;
    for (int i = 0; i < 3; ++i) {
        const double sum = m[i][0] + m[i][1] + m[i][2];
        for (int j = 0; j < 3; ++j)
            out[i][j] = m[i][j] * (white[i] / sum);
    }
    return out;
}

constexpr Matrix3 kRgbToXyz = onto_white(kPublishedRgbToXyz, {kWhiteX, kWhiteY, kWhiteZ});

// The exact inverse rather than a rounded published one, so that
// sRGB -> Lab -> sRGB round trips to machine precision.
constexpr Matrix3 inverse(const Matrix3 &m)
{
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    return {{
        {c00 / det, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det,
         (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det},
        {c01 / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
         (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det},
        {c02 / det, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det,
         (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det},
    }};
}

constexpr Matrix3 kXyzToRgb = inverse(kRgbToXyz);

// CIELAB's f(t): a cube root, replaced below delta^3 by the tangent line
// through (0, 4/29) so the slope stays finite at black.
constexpr double kDelta = 6.0 / 29.0;

double lab_f(double t)
{
    if (t > kDelta * kDelta * kDelta)
        return std::cbrt(t);
    return t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
}

double lab_f_inverse(double u)
{
    if (u > kDelta)
        return u * u * u;
    return 3.0 * kDelta * kDelta * (u - 4.0 / 29.0);
}

double wrap_degrees(double hue)
{
    double h = std::fmod(hue, 360.0);
    if (h < 0.0)
        h += 360.0;
    // fmod of a tiny negative number plus 360 rounds to 360 itself.
    return h >= 360.0 ? 0.0 : h;
}

// Relative luminance of v * top (encoded sRGB) and its derivative in v.
struct LuminanceSlope {
    double y, dy_dv;
};

LuminanceSlope luminance_at(const Rgb &top, double v)
{
    LuminanceSlope out{0.0, 0.0};
    const double channel[3] = {top.r, top.g, top.b};
    for (int i = 0; i < 3; ++i) {
        const double c = v * channel[i];
        double lin, slope;
        if (c <= 0.04045) {
            lin = c / 12.92;
            slope = 1.0 / 12.92;
        } else {
            const double base = (c + 0.055) / 1.055;
            lin = std::pow(base, 2.4);
            slope = 2.4 / 1.055 * lin / base;
        }
        out.y += kRgbToXyz[1][i] * lin;
        out.dy_dv += kRgbToXyz[1][i] * slope * channel[i];
    }
    return out;
}

// The v in [0,1] at which v * top has luminance target_y, for a top (the
// v = 1 colour) brighter than that.  Luminance is increasing in v, so this
// is a bracketed search; Newton steps make it a few iterations instead of
// forty bisections, falling back to bisection whenever a step would leave
// the bracket.  The sRGB decoding curve is convex (its linear toe is
// shallower than the power segment), so luminance is convex in v and Newton
// from above the root descends onto it without overshooting.  The start is
// the pure power law's answer: lin(x) / x^2.4 falls with x, hence
// Y(v) >= v^2.4 Y(1), so it lies at or above the root.
double value_for_luminance(const Rgb &top, double top_y, double target_y)
{
    if (target_y <= 0.0)
        return 0.0;
    double lo = 0.0, hi = 1.0;
    double v = std::pow(target_y / top_y, 1.0 / 2.4);
    for (int i = 0; i < 100; ++i) {
        const LuminanceSlope at = luminance_at(top, v);
        const double excess = at.y - target_y;
        if (excess == 0.0)
            return v;
        (excess > 0.0 ? hi : lo) = v;
        double next = v - excess / at.dy_dv;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (std::abs(next - v) <= 1e-15)
            return next;
        v = next;
    }
    return v;
}

} // namespace

Rgb hsv_to_rgb(double hue_degrees, double s, double v)
{
    const double h = wrap_degrees(hue_degrees) / 60.0;
    const int sector = std::min(static_cast<int>(h), 5);
    const double f = h - sector;
    const double p = v * (1.0 - s);
    const double q = v * (1.0 - s * f);
    const double t = v * (1.0 - s * (1.0 - f));
    switch (sector) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
    }
}

double srgb_to_linear(double c)
{
    if (c <= 0.04045)
        return c / 12.92;
    return std::pow((c + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double c)
{
    if (c <= 0.0031308)
        return 12.92 * c;
    return 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

Lab srgb_to_lab(const Rgb &c)
{
    const std::array<double, 3> lin = {srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)};
    std::array<double, 3> xyz{};
    for (int i = 0; i < 3; ++i)
        xyz[i] = kRgbToXyz[i][0] * lin[0] + kRgbToXyz[i][1] * lin[1] + kRgbToXyz[i][2] * lin[2];
    const double fx = lab_f(xyz[0] / kWhiteX);
    const double fy = lab_f(xyz[1] / kWhiteY);
    const double fz = lab_f(xyz[2] / kWhiteZ);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Rgb lab_to_srgb(const Lab &c)
{
    const double fy = (c.L + 16.0) / 116.0;
    const double fx = fy + c.a / 500.0;
    const double fz = fy - c.b / 200.0;
    const std::array<double, 3> xyz = {kWhiteX * lab_f_inverse(fx), kWhiteY * lab_f_inverse(fy),
                                       kWhiteZ * lab_f_inverse(fz)};
    std::array<double, 3> lin{};
    for (int i = 0; i < 3; ++i)
        lin[i] = kXyzToRgb[i][0] * xyz[0] + kXyzToRgb[i][1] * xyz[1] + kXyzToRgb[i][2] * xyz[2];
    return {linear_to_srgb(lin[0]), linear_to_srgb(lin[1]), linear_to_srgb(lin[2])};
}

double chroma(const Lab &c)
{
    return std::hypot(c.a, c.b);
}

double vividness(double hue, double s, double v)
{
    return chroma(srgb_to_lab(hsv_to_rgb(hue, s, v))) / chroma(srgb_to_lab(hsv_to_rgb(hue, 1.0, 1.0)));
}

// The search walks a path through the hue's (s, v) square: for each s, v(s)
// is the value whose L* is the target.  Because hsv(h,s,v) = v * hsv(h,s,1)
// channel by channel and every channel's linearisation is increasing, the
// luminance, hence L*, increases strictly with v, so a bracketed inner
// search (value_for_luminance) finds v(s).  Where even v = 1 is too dark
// (L*(h,s,1) falls as s grows, from 100 at white to the pure hue's L*), the
// path follows the v = 1 edge instead, giving up lightness.  The path is
// continuous, starts at vividness 0 (s = 0, a grey) and ends at s = 1.
//
// Vividness along the path increases with s wherever v(s) < 1 (checked on a
// grid: every integer hue, L* 1..99, 401 values of s).  On the v = 1 edge it
// does too, except for hues of about 316-322 degrees: where the smallest
// channel 1 - s crosses the sRGB curve's linear toe (s ~ 0.96) chroma wobbles
// by up to ~2e-5 and briefly exceeds the pure hue's (vividness ~1.0002).  The
// outer bisection does not need monotonicity: vividness(s = 0) = 0, and when
// vividness(s = 1) is at or above the target the interval stays bracketed and
// continuity guarantees a crossing (one of several, inside the wobble).  It is
// needed only to call a target above vividness(s = 1) unreachable; that case
// arises only when the path ends inside the slice (on the edge, s = 1 is the
// pure hue, vividness exactly 1 >= any clamped target), where monotonicity
// holds, so no scan for an interior maximum is necessary.  s = 1 is then the
// most vivid colour of the requested lightness and is returned inexact.
LightVivid colour_for(double hue, double target_L, double target_vividness)
{
    if (!std::isfinite(hue) || !std::isfinite(target_L) || !std::isfinite(target_vividness))
        throw std::invalid_argument("colour_for: hue, lightness and vividness must be finite");

    constexpr int kIterations = 40;
    constexpr double kExactL = 1e-6;
    constexpr double kExactVividness = 1e-6;

    const double h = wrap_degrees(hue);
    const double L = std::clamp(target_L, 0.0, 100.0);
    const double vivid = std::clamp(target_vividness, 0.0, 1.0);
    const double target_y = kWhiteY * lab_f_inverse((L + 16.0) / 116.0);
    const double pure_chroma = chroma(srgb_to_lab(hsv_to_rgb(h, 1.0, 1.0)));

    const auto value_for = [&](double s) {
        const Rgb top = hsv_to_rgb(h, s, 1.0);
        const double top_y = luminance_at(top, 1.0).y;
        return top_y <= target_y ? 1.0 : value_for_luminance(top, top_y, target_y);
    };
    const auto vividness_at = [&](double s, double v) {
        return chroma(srgb_to_lab(hsv_to_rgb(h, s, v))) / pure_chroma;
    };

    double s = 1.0;
    double v = value_for(s);
    if (vivid <= 0.0) {
        s = 0.0; // the bisection would only approach the grey
        v = value_for(s);
    } else if (vividness_at(s, v) > vivid) {
        double lo = 0.0, hi = 1.0;
        for (int i = 0; i < kIterations; ++i) {
            const double mid = 0.5 * (lo + hi);
            (vividness_at(mid, value_for(mid)) < vivid ? lo : hi) = mid;
        }
        s = 0.5 * (lo + hi);
        v = value_for(s);
    }

    LightVivid out{};
    out.rgb = hsv_to_rgb(h, s, v);
    out.s = s;
    out.v = v;
    out.achieved_L = srgb_to_lab(out.rgb).L;
    out.achieved_vividness = vividness_at(s, v);
    // A clamped target was not met, however close the clamped one came.
    out.exact = L == target_L && vivid == target_vividness && std::abs(out.achieved_L - L) <= kExactL &&
                std::abs(out.achieved_vividness - vivid) <= kExactVividness;
    return out;
}

} // namespace arbor::tf
