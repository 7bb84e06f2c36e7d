// shape_choice.hpp - an opacity shape for each branch from its topology and
// measures, the thesis' first item of future work.  Thin structures (skin,
// skull: sheets and shells, compactness below 0.2, see branch_tree.h) read
// best as surfaces: a narrow isovalue peak when about a voxel thick, a hat
// around the middle of their interval when thicker.  Solid structures (a tumour, a bone) are
// told apart by where their voxels' values lie between saddle and extremum,
// phi = relative hypervolume / (persistence * volume): near the extremum
// (phi >= 0.55, a plateau) a box shows all of the structure evenly; spread
// (0.25 .. 0.55) a ramp makes its core denser; near the saddle (< 0.25, a
// bulk with a spike) an inverse ramp shows the bulk.  The root, the body as
// a whole, keeps the ramp.
#pragma once

#include "opacity_shape.hpp"

#include <arbor/sdk/branch_tree.hpp>

#include <string>

namespace arbor::tf {

struct ShapeChoice {
    OpacityShape shape = OpacityShape::Ramp;
    std::string why; // one line for the report
};

// `min_spacing`: the volume's smallest voxel spacing, mm.
ShapeChoice choose_shape(const sdk::BranchTreeView &tree, uint32_t branch, double min_spacing);

} // namespace arbor::tf
