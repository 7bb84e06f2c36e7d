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

// How the contour tree's work space is laid out (see below).
enum class TreeMemoryPlan { Parallel, Sequential, Streamed };

struct TopologyResult {
    ContourTree tree;
    BranchDecomposition branches;
    std::vector<StageTiming> timings;
    double total_seconds = 0.0;
    TreeMemoryPlan plan = TreeMemoryPlan::Parallel; // how the tree was computed
};

// stage ("sorting", "join tree"...) and fraction in [0, 1]; may throw to
// cancel.  Called on the calling thread only.
using StageProgressFn = std::function<void(const char *stage, double fraction)>;

// How compute_contour_tree lays out its work space, fastest first.  Beyond
// the volume, at its peak:
// - Parallel: the vertex order (4 bytes a voxel), the merge state (12) and
//   its label words (4), and the split sweep's own component words (4),
//   both sweeps at once: 27;
// - Sequential: the sweeps one after the other, the split sweep reusing the
//   label words for its components, as the join sweep did: 23;
// - Streamed (8- and 16-bit volumes): no whole order either; each walk of it
//   makes the order an eighth at a time by scanning the values, on a second
//   thread, holding two eighths (1 byte a voxel): 20.
// Each includes up to 3 bytes a voxel for the tree's nodes and arcs and the
// merge's lists (2.3 on an unfiltered CT, a node per 20 voxels).  The
// segmentation the merge leaves (vertex_arc, 4) is written in place of the
// merge state, so it adds nothing.
const char *tree_memory_plan_name(TreeMemoryPlan plan);
inline constexpr uint64_t kContourTreeWorkBytesPerVoxel = 23;         // Sequential
inline constexpr uint64_t kContourTreeParallelWorkBytesPerVoxel = 27; // Parallel
inline constexpr uint64_t kContourTreeStreamedWorkBytesPerVoxel = 20; // Streamed
inline constexpr uint32_t kStreamedOrderPieces = 8;
inline uint64_t contour_tree_work_bytes(uint64_t voxels, TreeMemoryPlan plan)
{
    switch (plan) {
    case TreeMemoryPlan::Parallel: return voxels * kContourTreeParallelWorkBytesPerVoxel;
    case TreeMemoryPlan::Sequential: return voxels * kContourTreeWorkBytesPerVoxel;
    case TreeMemoryPlan::Streamed: return voxels * kContourTreeStreamedWorkBytesPerVoxel;
    }
    return voxels * kContourTreeParallelWorkBytesPerVoxel;
}
// The least work space a volume of `type` can have its tree computed in.
uint64_t least_contour_tree_work_bytes(uint64_t voxels, arbor_voxel_type type);

// The fastest plan whose work space takes at most half of `memory_budget`
// (the other half is left to the rest of the run: the renderer's copies of
// the volume, a workstation's views, other programs), else the one that
// takes least.  A whole-body CT (512 x 512 x 2000) on a 24 GB machine is
// streamed; a 512 x 512 x 300 chest CT sweeps in parallel.
TreeMemoryPlan choose_tree_memory_plan(uint64_t voxels, arbor_voxel_type type, uint64_t memory_budget);

// The contour tree alone (result.branches left empty).  Throws
// std::invalid_argument for volumes with NaN or infinite values (naming how
// many and where) and for empty volumes.  A stop request on `stop` is seen
// by both sweeps and by every stage, which then unwind with Cancelled.  The
// plan is choose_tree_memory_plan's for `memory_budget` (result.plan).
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
