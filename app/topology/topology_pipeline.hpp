// topology_pipeline.hpp - from a volume to its contour tree and branch
// decomposition: order the vertices, sweep the join and split trees (in
// parallel), merge them, decompose into branches with measures.  Reports
// progress per stage and the time each stage took.
#pragma once

#include "branch_decomposition.hpp"
#include "contour_tree.hpp"

#include "core/volume.hpp"

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
// itself: the merge's, with the vertex order (4 bytes a voxel), both merge
// trees (5 + 5) and the merge state (16), plus about 1 byte a voxel for the
// nodes and arcs of a noisy CT's tree (a node per 20 voxels).  Callers check
// it against the memory available before they start.
inline constexpr uint64_t kContourTreeWorkBytesPerVoxel = 31;
inline uint64_t contour_tree_work_bytes(uint64_t voxels) { return voxels * kContourTreeWorkBytesPerVoxel; }

// The contour tree alone (result.branches left empty).  Throws
// std::invalid_argument for volumes with NaN or infinite values (naming how
// many and where) and for empty volumes.  A stop request on `stop` is seen
// by both sweeps (the split tree runs on a second thread) and by every
// stage, which then unwind with Cancelled.
TopologyResult compute_contour_tree(const Volume &volume, const StageProgressFn &progress = {},
                                    std::stop_token stop = {});

// (Re)decomposes result.tree into branches ranked by `importance`, adding
// the stage's time: simplifiers compared on one volume share one tree.
void decompose(TopologyResult &result, const Volume &volume, const ImportanceFn &importance,
               const StageProgressFn &progress = {}, std::stop_token stop = {});

// Both: compute_contour_tree, then decompose.
TopologyResult compute_topology(const Volume &volume, const ImportanceFn &importance,
                                const StageProgressFn &progress = {}, std::stop_token stop = {});

} // namespace arbor::topology
