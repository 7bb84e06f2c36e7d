// importance_knee.hpp - an automatic branch count: where the curve of
// importance against rank bends from the few strong structures into the long
// flat tail of noise.  Kneedle (Satopaa et al. 2011) on log importance
// against rank over the 50 most important branches: the rank farthest below
// the chord from the first to the last point, which is kept (Kneedle's knee
// is the last point before the flat tail).  Log importance, because ITri
// spans orders of magnitude; a window of 50, because the knee sits among the
// first few dozen on every volume we have (phantom 11-12, tooth 8, engine
// 16, bonsai 8, MR brain 17), while longer windows drift into the noise.
#pragma once

#include "branch_decomposition.hpp"

#include <cstddef>
#include <vector>

namespace arbor::topology {

struct KneeChoice {
    std::size_t keep = 1;         // branches to keep, root included
    std::size_t considered = 0;   // ranks the knee was looked for in
};

// Looks at the `max_ranks` most important non-root branches (of those
// `eligible` marks, when it is not empty); the result is clamped to
// [min_keep, max_keep].
KneeChoice knee_branch_count(const BranchDecomposition &d, std::size_t min_keep = 6, std::size_t max_keep = 48,
                             std::size_t max_ranks = 50, const std::vector<bool> &eligible = {});

} // namespace arbor::topology
