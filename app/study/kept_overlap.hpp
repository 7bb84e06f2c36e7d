// kept_overlap.hpp - how far two simplifications of one contour tree keep
// the same structures.  Different importances pick different
// representative extrema for one structure, so kept branch a (of A) and b
// (of B) are the same structure when each one's extremum lies in the
// other's region.  The label of a node under a cut needs no label map: it is
// the nearest kept ancestor of the branch the node continues (node_branch),
// so this costs O(kept x depth) per pair of cuts.  The root, kept by all, is
// left out.
#pragma once

#include "topology/branch_decomposition.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace arbor::study {

struct KeptOverlap {
    std::size_t shared = 0, only_a = 0, only_b = 0;
    double jaccard = 1.0; // shared / union (1 when both keep only the root)
};

// Both decompositions are of the same contour tree (the same nodes); `kept_a`
// and `kept_b` are their cuts' kept branches, root first (SimplificationCut::kept).
KeptOverlap kept_overlap(const topology::BranchDecomposition &a, const std::vector<uint32_t> &kept_a,
                         const topology::BranchDecomposition &b, const std::vector<uint32_t> &kept_b);

} // namespace arbor::study
