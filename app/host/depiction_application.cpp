#include "depiction_application.hpp"

#include <algorithm>
#include <cmath>

namespace arbor {

double depiction_opacity(const arbor_depiction &d, const arbor_branch_tree &tree, uint32_t b, double value)
{
    const double at_saddle = d.opacity_at_saddle[b], at_extremum = d.opacity_at_extremum[b];
    const double s = tree.saddle_value[b], e = tree.extremum_value[b];
    if (s == e)
        return at_extremum;
    const double t = std::clamp((value - s) / (e - s), 0.0, 1.0);
    return at_saddle + (at_extremum - at_saddle) * t;
}

Rgb depiction_colour(const arbor_depiction &d, uint32_t b, const Rgb &colour)
{
    Rgb c = colour;
    if (!std::isnan(d.hue[b])) {
        std::array<double, 3> hsv = rgb_to_hsv(c);
        hsv[0] = d.hue[b];
        c = hsv_to_rgb(hsv);
    }
    const double saturation = std::clamp(static_cast<double>(d.saturation[b]), 0.0, 1.0);
    if (saturation != 1.0) {
        Lab lab = rgb_to_lab(c);
        lab[1] *= saturation;
        lab[2] *= saturation;
        c = lab_to_rgb(lab);
    }
    for (double &x : c)
        x = std::clamp(x, 0.0, 1.0);
    return c;
}

namespace {

void apply_to(const arbor_depiction &d, const arbor_branch_tree &tree, uint32_t b, double value, float *rgba)
{
    const Rgb c = depiction_colour(d, b, {rgba[0], rgba[1], rgba[2]});
    for (int k = 0; k < 3; ++k)
        rgba[k] = static_cast<float>(c[k]);
    rgba[3] = static_cast<float>(std::clamp(rgba[3] * depiction_opacity(d, tree, b, value), 0.0, 1.0));
}

} // namespace

void apply_depiction(const arbor_depiction &d, const arbor_branch_tree &tree, arbor_tf_set &set,
                     arbor_tf_point *points)
{
    const uint32_t n = std::min({set.branch_count, d.branch_count, tree.branch_count});
    for (uint32_t b = 0; b < n; ++b) {
        const double lo = set.domain[2 * b], hi = set.domain[2 * b + 1];
        float *lut = set.lut + std::size_t{b} * set.lut_size * 4;
        for (uint32_t i = 0; i < set.lut_size; ++i)
            apply_to(d, tree, b, lo + (hi - lo) * i / (set.lut_size - 1.0), lut + 4 * i);
        if (points)
            for (uint32_t i = set.point_offsets[b]; i < set.point_offsets[b + 1]; ++i)
                apply_to(d, tree, b, points[i].value, points[i].rgba);
    }
}

} // namespace arbor
