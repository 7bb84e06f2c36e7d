// colour_space.hpp - the colour spaces the transfer-function generators work
// in: HSV for choosing hues, sRGB for output and CIELAB (D65) for perceptual
// lightness and chroma, plus the thesis' vividness (eq. 6.12/6.13) and the
// search for a colour of a given hue, lightness and vividness.
#pragma once

namespace arbor::tf {

// Straight (not premultiplied), gamma-encoded sRGB; in-gamut values lie in [0,1].
struct Rgb {
    double r, g, b;
};

// CIELAB relative to the D65 white point.
struct Lab {
    double L, a, b;
};

// Hexcone HSV to sRGB.  The hue wraps modulo 360; s and v are in [0,1].
Rgb hsv_to_rgb(double hue_degrees, double s, double v);

// The IEC 61966-2-1 transfer curves between encoded and linear sRGB.
double srgb_to_linear(double c);
double linear_to_srgb(double c);

Lab srgb_to_lab(const Rgb &c);
// Not clamped: an out-of-gamut Lab gives components outside [0,1].
Rgb lab_to_srgb(const Lab &c);

double chroma(const Lab &c);

// Chroma of hsv(h,s,v) relative to that of the pure hue hsv(h,1,1)
// (thesis eq. 6.12/6.13): 0 for greys, 1 for the pure hue.  It can exceed 1
// very slightly (by at most ~2e-4, hues near 319 degrees, s ~ 0.96, v = 1).
double vividness(double hue, double s, double v);

struct LightVivid {
    Rgb rgb;
    double s, v;
    double achieved_L, achieved_vividness;
    bool exact; // both targets met (to ~1e-6)
};

// The colour of HSV hue `hue` whose CIELAB L* is target_L (0..100) and whose
// vividness is target_vividness (0..1), found in the hue's HSV slice; targets
// outside those ranges are clamped (and the result is then not exact).  When
// no colour of the hue meets both, exact is false and the result is the
// nearest point of the search path: too vivid for that lightness gives the
// requested L* at the highest vividness it allows (s = 1); too light for that
// vividness gives the requested vividness at v = 1, as light as it allows.
// Throws std::invalid_argument for non-finite arguments.
LightVivid colour_for(double hue, double target_L, double target_vividness);

} // namespace arbor::tf
