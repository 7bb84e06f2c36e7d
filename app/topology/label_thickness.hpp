// label_thickness.hpp - how thick each labelled structure is, and how
// compact: thickness is twice its volume over the area of its boundary with
// other labels (faces on the grid's own border do not count: the scan was
// cut there, the structure was not), the face area divided by 1.5, what the
// voxel faces of a smooth surface add up to on average.  A shell is as
// thick as the shell, a slab as the slab, a ball of radius r 2r/3.
// Compactness is the thickness over the cube root of the volume: about 0.4
// for a ball, 0.25 for a vessel twenty times as long as it is wide, below
// 0.1 for a shell such as the skull.  Together they tell thin structures
// (skin, skull) from solid ones (a tumour, a bone, a vessel), which want
// different transfer functions.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace arbor::topology {

struct LabelShape {
    double thickness_mm = 0.0;
    double compactness = 0.0;
    // Of its voxels' faces toward other labels or out of the grid, the share
    // (by area) on the grid's own border: how much of it the field of view
    // cut.  An arm cut by a chest CT's field of view, or a headrest running
    // the scan's length, is a slab along the border (0.1 and more); a
    // structure inside the body meets the border with its cross-sections
    // only (the spine of a chest CT: about 0.03).
    double cut_fraction = 0.0;
    // The share of its voxels outside the body (core/body_region.hpp: a
    // headrest, a table, an arm lying apart); filled in by the pipeline,
    // which knows the scan's background, 0 here.
    double outside_body = 0.0;
};

// `labels`: one per voxel, i fastest, each < label_count.  A label that
// touches no other (it fills the grid) is as thick as the cube root of its
// volume (compactness 1); a label without voxels gets zeros.
std::vector<LabelShape> label_shapes(std::span<const uint32_t> labels, const std::array<int64_t, 3> &dims,
                                     const std::array<double, 3> &spacing, uint32_t label_count);

} // namespace arbor::topology
