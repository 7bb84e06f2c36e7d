// label_colors.hpp - distinguishable display colours for branch labels, used
// by label-map colour tables and comparison images until the transfer
// functions give branches their own colours.
#pragma once

#include <array>
#include <cstdint>

namespace arbor::io {

using Rgb8 = std::array<uint8_t, 3>;

// Label 0 (the root branch: background and everything simplified into it)
// is dark grey; label k > 0 gets the hue k * 137.5 degrees (the golden
// angle), so neighbouring labels differ strongly, at alternating lightness.
Rgb8 label_color(uint32_t label);

} // namespace arbor::io
