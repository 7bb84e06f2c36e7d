// opacity_shape.hpp - how opacity varies inside a branch's scalar interval:
// t runs from 0 at the saddle to 1 at the extremum, and a shape maps it into
// the branch's opacity range [low, high] (thesis §6.4.3).
#pragma once

#include <string>
#include <vector>

namespace arbor::tf {

enum class OpacityShape { Ramp, InverseRamp, Hat, Box, Peak };

// Names as on the command line: ramp, inverse-ramp, hat, box, peak.
const std::vector<std::string> &opacity_shape_names();

struct ShapeSettings {
    OpacityShape shape = OpacityShape::Ramp;
    double peak_position = 0.5; // Peak: where the isovalue lies, t in [0, 1]
    double peak_width = 0.1;    // Peak: full width at the base, in t
};

// Opacity at t in [0, 1] for the range [low, high].
double shape_opacity(const ShapeSettings &s, double t, double low, double high);

// The t of the shape's corners (its control points), ascending, 0 and 1 included.
std::vector<double> shape_corners(const ShapeSettings &s);

} // namespace arbor::tf
