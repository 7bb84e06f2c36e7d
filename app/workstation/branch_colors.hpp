// branch_colors.hpp - the colour each view gives a branch: its transfer
// function's colour weighted by opacity (what the 3D view shows it in), so
// the slice overlay, the tree, the branch list and the 3D view agree.
#pragma once

#include "host/tf_generation.hpp"

#include <array>
#include <vector>

namespace arbor::workstation {

// Per branch, sRGB in [0, 1]; a branch without opacity gets the
// distinguishable label colour (io/label_colors.hpp).
std::vector<std::array<float, 3>> branch_colors(const TransferFunctions &functions);

// The same hues made vivid for drawing over grey slices (a pale, desaturated
// transfer-function colour vanishes over bone): saturation at least 0.65
// and value at least 0.9; a grey branch gets its distinguishable label hue.
std::vector<std::array<float, 3>> overlay_colors(const std::vector<std::array<float, 3>> &colors);

} // namespace arbor::workstation
