#include "control_points.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <xxhash.h>

namespace arbor::pipeline {

float file_component(float x)
{
    return static_cast<float>(std::round(x * 1e6) / 1e6);
}

std::string points_digest(const arbor_tf_point *points, std::size_t count)
{
    // Each point's value and its four file components, bit for bit.
    std::vector<unsigned char> bytes(count * (sizeof(double) + 4 * sizeof(float)));
    unsigned char *at = bytes.data();
    for (std::size_t i = 0; i < count; ++i) {
        std::memcpy(at, &points[i].value, sizeof(double));
        at += sizeof(double);
        for (float c : points[i].rgba) {
            const float f = file_component(c);
            std::memcpy(at, &f, sizeof f);
            at += sizeof f;
        }
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx",
                  static_cast<unsigned long long>(XXH3_64bits(bytes.data(), bytes.size())));
    return text;
}

void bake_from_points(const arbor_tf_point *points, std::size_t count, std::pair<double, double> domain,
                      uint32_t lut_size, float *rgba)
{
    std::size_t next = 0; // the first point above the current value
    for (uint32_t i = 0; i < lut_size; ++i) {
        const double v = domain.first + (domain.second - domain.first) * i / (lut_size - 1.0);
        while (next < count && points[next].value <= v)
            ++next;
        float *out = rgba + 4 * std::size_t{i};
        if (next == 0) {
            std::memcpy(out, points[0].rgba, sizeof points[0].rgba);
        } else if (next == count) {
            std::memcpy(out, points[count - 1].rgba, sizeof points[count - 1].rgba);
        } else {
            const arbor_tf_point &a = points[next - 1], &b = points[next];
            const double t = (v - a.value) / (b.value - a.value); // b.value > v >= a.value
            for (int k = 0; k < 4; ++k)
                out[k] = static_cast<float>(a.rgba[k] + (b.rgba[k] - a.rgba[k]) * t);
        }
    }
}

} // namespace arbor::pipeline
