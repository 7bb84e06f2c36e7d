// tree_check.hpp - the structural invariants of a contour tree, checked on
// trees that come from outside the process (the on-disk tree cache).
//
// A tree read back from a file may be damaged in ways a checksum cannot see
// (a bug in the writer, a hand-made file).  Every index the branch
// decomposition and the measures follow is checked here before the tree is
// used, so a bad tree is refused with a reason instead of reading out of
// bounds or looping: node and arc indices in range, arcs running from a lower
// to a higher node (so walks upwards end), incidence lists that agree with
// the arcs and the node degrees, node kinds that match their degrees, and a
// segmentation that only names existing arcs.
#pragma once

#include "topology/contour_tree.hpp"

#include <cstdint>
#include <string>

namespace arbor::pipeline {

// The first defect found in `tree`, as a sentence; empty when `tree` is a
// consistent contour tree of a volume of `vertex_count` voxels.
std::string find_tree_defect(const topology::ContourTree &tree, uint64_t vertex_count);

} // namespace arbor::pipeline
