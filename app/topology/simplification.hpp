// simplification.hpp - cutting the branch hierarchy: keep the branches whose
// importance exceeds a threshold, or the N most important ones, and label
// every voxel with the kept branch it falls in.
//
// A removed branch's voxels go to its nearest kept ancestor; a kept branch
// whose parent was removed hangs off that ancestor too.  The root is always
// kept.  With a monotone importance (persistence, volume, ITri on relative
// measures) a child of the same kind as its parent is never more important
// than it, but a child of the other kind can be (a deep pit inside a low
// peak), so a cut need not be a subtree: the nearest-kept-ancestor rule makes
// every cut well defined.
#pragma once

#include "branch_decomposition.hpp"

#include "core/label_map.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace arbor::topology {

struct SimplificationCut {
    std::vector<uint32_t> kept;       // branch indices of the full decomposition, root first
    std::vector<int32_t> kept_index;  // per branch: index in `kept`, or -1
    std::vector<uint32_t> label_of;   // per branch: index in `kept` of its nearest kept ancestor (or itself)
    std::vector<int32_t> kept_parent; // per kept branch: index in `kept` of its nearest kept ancestor
};

// Keep branches with importance > threshold.  `eligible`, when not empty,
// has one entry per branch: a branch marked false is never kept (the
// background's basins are not structures), whatever its importance.
SimplificationCut cut_by_threshold(const BranchDecomposition &d, double threshold,
                                   const std::vector<bool> &eligible = {});
// Keep the `count` most important eligible branches (root included; ties by index).
SimplificationCut cut_by_count(const BranchDecomposition &d, std::size_t count,
                               const std::vector<bool> &eligible = {});

// Voxel -> index in cut.kept, for every voxel of the tree's volume.
LabelMap label_voxels(const ContourTree &tree, const BranchDecomposition &d, const SimplificationCut &cut);

} // namespace arbor::topology
