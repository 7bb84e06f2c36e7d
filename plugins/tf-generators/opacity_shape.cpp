#include "opacity_shape.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::tf {

const std::vector<std::string> &opacity_shape_names()
{
    static const std::vector<std::string> names{"ramp", "inverse-ramp", "hat", "box", "peak"};
    return names;
}

double shape_opacity(const ShapeSettings &s, double t, double low, double high)
{
    t = std::clamp(t, 0.0, 1.0);
    double w = 0.0; // 0 -> low, 1 -> high
    switch (s.shape) {
    case OpacityShape::Ramp: w = t; break;
    case OpacityShape::InverseRamp: w = 1.0 - t; break;
    case OpacityShape::Hat: w = 1.0 - std::fabs(2.0 * t - 1.0); break;
    case OpacityShape::Box: w = 1.0; break;
    case OpacityShape::Peak: {
        const double half = std::max(s.peak_width / 2.0, 1e-9);
        w = std::max(0.0, 1.0 - std::fabs(t - s.peak_position) / half);
        break;
    }
    }
    return low + (high - low) * w;
}

std::vector<double> shape_corners(const ShapeSettings &s)
{
    std::vector<double> t{0.0, 1.0};
    if (s.shape == OpacityShape::Hat)
        t.push_back(0.5);
    if (s.shape == OpacityShape::Peak)
        for (double x : {s.peak_position - s.peak_width / 2, s.peak_position, s.peak_position + s.peak_width / 2})
            if (x > 0.0 && x < 1.0)
                t.push_back(x);
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    return t;
}

} // namespace arbor::tf
