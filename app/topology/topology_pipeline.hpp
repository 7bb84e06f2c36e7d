// topology_pipeline.hpp - from a volume to its contour tree and branch
// decomposition: order the vertices, sweep the join and split trees (in
// parallel), merge them, decompose into branches with measures.  Reports
// progress per stage and the time each stage took.
#pragma once

#include "branch_decomposition.hpp"
#include "contour_tree.hpp"

#include "core/volume.hpp"

#include <cstdint>
#include <functional>
#include <stop_token>
#include <string>
#include <vector>

namespace arbor::topology {

struct StageTiming {
    std::string stage;
    double seconds = 0.0;
};

struct TopologyResult {
    ContourTree tree;
    BranchDecomposition branches;
    std::vector<StageTiming> timings;
    double total_seconds = 0.0;
};

// stage ("sorting", "join tree"...) and fraction in [0, 1]; may throw to
// cancel.  Called on the calling thread only.
using StageProgressFn = std::function<void(const char *stage, double fraction)>;

// Work space compute_contour_tree needs at its peak, beyond the volume
// itself, during the sweeps: the vertex order (4 bytes a voxel) and the merge
// state (16), plus the split sweep's own component words (4) when the two
// sweeps run at once; and up to 3 bytes a voxel for the tree's nodes and arcs
// and the merge's lists (2.3 on an unfiltered CT, a node per 20 voxels).  The
// merge needs no more: it frees the order before it allocates the
// segmentation (4).
inline constexpr uint64_t kContourTreeWorkBytesPerVoxel = 23;         // sweeps one after the other
inline constexpr uint64_t kContourTreeParallelWorkBytesPerVoxel = 27; // both sweeps at once
inline uint64_t contour_tree_work_bytes(uint64_t voxels, bool parallel = false)
{
    return voxels * (parallel ? kContourTreeParallelWorkBytesPerVoxel : kContourTreeWorkBytesPerVoxel);
}

// The contour tree alone (result.branches left empty).  Throws
// std::invalid_argument for volumes with NaN or infinite values (naming how
// many and where) and for empty volumes.  A stop request on `stop` is seen
// by both sweeps and by every stage, which then unwind with Cancelled.  The
// two sweeps run at once (the split tree on a second thread) when
// `memory_budget` bytes hold contour_tree_work_bytes(voxels, true), one
// after the other otherwise (4 bytes a voxel less, twice the time).
TopologyResult compute_contour_tree(const Volume &volume, const StageProgressFn &progress = {},
                                    std::stop_token stop = {}, uint64_t memory_budget = UINT64_MAX);

// (Re)decomposes result.tree into branches ranked by `importance`, adding
// the stage's time: simplifiers compared on one volume share one tree.
void decompose(TopologyResult &result, const Volume &volume, const ImportanceFn &importance,
               const StageProgressFn &progress = {}, std::stop_token stop = {});

// Both: compute_contour_tree, then decompose.
TopologyResult compute_topology(const Volume &volume, const ImportanceFn &importance,
                                const StageProgressFn &progress = {}, std::stop_token stop = {},
                                uint64_t memory_budget = UINT64_MAX);

} // namespace arbor::topology
