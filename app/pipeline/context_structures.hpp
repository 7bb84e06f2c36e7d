// context_structures.hpp - which kept structures are not the anatomy the
// picture is about, and are drawn as faint context (the visibility balance's
// `context_cap`) instead of taking the picture:
//   - an object outside the body: a peak (material, not an air cavity: a
//     nasal cavity opens to the outside, yet is anatomy) with at least half
//     its voxels outside the body region (core/body_region.hpp): a CT's
//     headrest or table, an MR's frame or marker, an arm lying apart;
//   - a slab the field of view cut: a fifth or more of its surface lies on
//     the scan's own border (topology/label_thickness.hpp's cut_fraction):
//     an arm cut by a chest CT's field of view, the top of a head cut by the
//     last slice.  A structure inside the body meets the border with its
//     cross-sections only (the CT head's mandible: 0.09).
// Faint rather than cropped: a reader still sees where the headrest or the
// arm is, and nothing of the scan is hidden without saying so.
#pragma once

#include "topology/label_thickness.hpp"

namespace arbor::pipeline {

enum class ContextReason { None, OutsideBody, CutByFieldOfView };

inline constexpr double kOutsideBody = 0.5;      // share of voxels outside the body
inline constexpr double kCutByFieldOfView = 0.2; // share of the surface on the scan's border

// `root`: the root branch (the body as a whole) is never context.
ContextReason context_reason(const topology::LabelShape &shape, bool maximum, bool root);

// "outside the body", "cut by the field of view", or "".
const char *describe(ContextReason reason);

} // namespace arbor::pipeline
