// background_level.hpp - which values of a scan are its background: the air
// around a CT, the dark noise around an MR, the empty space of a phantom.
// They must stay fully transparent (a haze of noise in the air otherwise
// takes most of the picture), and their basins are not structures to keep.
//
// From the histogram: the background is the fullest bin in the lowest 40 %
// of the value range, provided it stands out (five times the mean of the
// filled bins) and its peak holds a real share of the voxels; its level
// is where, going up from that peak, the smoothed histogram falls below a
// twentieth of the peak (the end of its noise's tail); a second peak at least
// half as full further up the low part (air inside a CT's field of view above
// the padding outside it) extends it; the level lies in the low part too.
// A scan without such a peak (cropped inside the body) has none.
#pragma once

#include "volume.hpp"

#include <optional>

namespace arbor {

struct BackgroundLevel {
    double peak = 0.0;     // stored value of the background's mode
    double level = 0.0;    // values <= level are background
    double fraction = 0.0; // of the voxels at or below the level
};

std::optional<BackgroundLevel> estimate_background(const Volume &volume);

} // namespace arbor
