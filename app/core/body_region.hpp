// body_region.hpp - where the body is in a scan, so that what lies outside
// it (a CT's headrest or table, an arm lying apart) can be told from the
// anatomy.  On a coarse grid of cells about 2 mm wide (the mean of each
// block of voxels):
//   1. what is above the body's threshold, halfway from the background
//      level (the air of a CT, an MR's noise) to the median of what lies
//      above it (a CT's pillow, foam at -800 HU, is not the body);
//   2. its holes filled in each slice (along the stored third axis): the
//      lungs, the airways and the sinuses lie inside the body, though they
//      hold air, and so does an MR's brain inside the dark skull;
//   3. eroded by a box of 4 mm each way, which removes every sheet thinner
//      than 8 mm (a headrest, a table top) and every contact that narrow;
//   4. the largest 6-connected component of what is left: the body's core;
//   5. dilated by the same box, within step 2's mask: the body to its skin.
// A scan with no background (cropped inside the body) is all body, and so
// is one whose largest piece holds less than half of what is above the
// threshold (a segmented vessel tree: no body to speak of).
#pragma once

#include "volume.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace arbor {

class BodyRegion {
public:
    // `background_level`: stored values at or below it are background; NaN
    // (none found) makes the whole grid the body.
    BodyRegion(const Volume &volume, double background_level);

    bool inside(int64_t i, int64_t j, int64_t k) const
    {
        return inside_[static_cast<std::size_t>(i / factor_[0] +
                                                cells_[0] * (j / factor_[1] + cells_[1] * (k / factor_[2])))] != 0;
    }

    // Per label (labels: one per voxel of the volume, i fastest, each <
    // label_count) the share of its voxels outside the body; 0 for a label
    // without voxels.
    std::vector<double> outside_shares(std::span<const uint32_t> labels, uint32_t label_count) const;

private:
    std::array<int64_t, 3> dims_{}, factor_{}, cells_{};
    std::vector<uint8_t> inside_; // per coarse cell
};

} // namespace arbor
