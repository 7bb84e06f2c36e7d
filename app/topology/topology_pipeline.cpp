#include "topology_pipeline.hpp"

#include "core/cancelled.hpp"
#include "core/stopwatch.hpp"

#include "grid_neighbors.hpp"
#include "merge_tree.hpp"
#include "order_pieces.hpp"
#include "vertex_order.hpp"

#include "core/volume_statistics.hpp"
#include "core/voxel_type.hpp"

#include <chrono>
#include <exception>
#include <stdexcept>
#include <thread>

namespace arbor::topology {

namespace {

void refuse_non_finite(const Volume &volume)
{
    if (is_integer_voxel_type(volume.type()))
        return;
    const VolumeStatistics s = compute_statistics(volume, 1);
    const int64_t bad = s.nan_count + s.infinite_count;
    if (bad == 0)
        return;
    const Geometry &g = volume.geometry();
    const int64_t v = s.first_non_finite;
    throw std::invalid_argument(
        "the volume has " + std::to_string(s.nan_count) + " NaN and " + std::to_string(s.infinite_count) +
        " infinite values (the first at voxel " + std::to_string(v % g.dims[0]) + ", " +
        std::to_string((v / g.dims[0]) % g.dims[1]) + ", " + std::to_string(v / (g.dims[0] * g.dims[1])) +
        "); a contour tree needs finite values everywhere, so fill or mask them first");
}

} // namespace

const char *tree_memory_plan_name(TreeMemoryPlan plan)
{
    switch (plan) {
    case TreeMemoryPlan::Parallel: return "parallel";
    case TreeMemoryPlan::Sequential: return "sequential";
    case TreeMemoryPlan::Streamed: return "streamed";
    }
    return "?";
}

uint64_t least_contour_tree_work_bytes(uint64_t voxels, arbor_voxel_type type)
{
    return contour_tree_work_bytes(voxels, orders_by_counting(type) ? TreeMemoryPlan::Streamed
                                                                    : TreeMemoryPlan::Sequential);
}

TreeMemoryPlan choose_tree_memory_plan(uint64_t voxels, arbor_voxel_type type, uint64_t memory_budget)
{
    const uint64_t room = memory_budget / 2;
    if (contour_tree_work_bytes(voxels, TreeMemoryPlan::Parallel) <= room)
        return TreeMemoryPlan::Parallel;
    if (contour_tree_work_bytes(voxels, TreeMemoryPlan::Sequential) <= room || !orders_by_counting(type))
        return TreeMemoryPlan::Sequential;
    return TreeMemoryPlan::Streamed;
}

TopologyResult compute_contour_tree(const Volume &volume, const StageProgressFn &progress, std::stop_token stop,
                                    uint64_t memory_budget)
{
    if (volume.empty() || volume.voxel_count() == 0)
        throw std::invalid_argument("cannot compute the topology of an empty volume");
    refuse_non_finite(volume);
    const auto report = [&](const char *stage) -> ProgressFn {
        return [&progress, &stop, stage](double f) {
            throw_if_stopped(stop);
            if (progress)
                progress(stage, f);
        };
    };
    // The split sweep's thread only polls: progress is the caller's thread's.
    const ProgressFn poll = [&stop](double) { throw_if_stopped(stop); };

    TopologyResult result;
    Stopwatch total, watch;
    const uint32_t n = static_cast<uint32_t>(volume.voxel_count());
    const Geometry &g = volume.geometry();

    result.plan = choose_tree_memory_plan(n, volume.type(), memory_budget);
    const bool parallel = result.plan == TreeMemoryPlan::Parallel;

    // Both sweeps fill one merge state.  They are independent: with memory
    // for the split sweep's own component words, it runs on a second thread;
    // otherwise after the join sweep, reusing the merge's label words, in
    // which the join sweep keeps its components.
    // Their memory is faulted in before they start, which on a virtual
    // machine alone takes seconds (core/huge_pages.hpp).  With the parallel
    // plan's memory and a counting sort (whose only other memory is the
    // order), that happens on a second thread while the vertices are sorted
    // on this one; the "memory" timing is then what is left of it after the
    // sort.
    // The state, indexed by rank, is read and written in order: small pages,
    // which fault in 3-4 times faster here.  The component words are read
    // at random by grid index: huge pages (core/huge_pages.hpp).
    UninitializedBuffer<MergeVertex> state;
    UninitializedBuffer<uint32_t> labels, split_components;
    const auto fault_in = [&] {
        state = UninitializedBuffer<MergeVertex>(n, Pages::Small);
        labels = UninitializedBuffer<uint32_t>(n);
        if (parallel)
            split_components = UninitializedBuffer<uint32_t>(n);
    };
    std::exception_ptr fault_error;
    std::jthread faulting; // joined before `state` goes, even when the sort throws
    if (parallel && orders_by_counting(volume.type()))
        faulting = std::jthread([&] {
            try {
                fault_in();
            } catch (...) {
                fault_error = std::current_exception();
            }
        });
    OrderPieces order = result.plan == TreeMemoryPlan::Streamed
                            ? OrderPieces(volume.type(), volume.data(), n,
                                          (n + kStreamedOrderPieces - 1) / kStreamedOrderPieces)
                            : OrderPieces(sort_vertices(volume.type(), volume.data(), n, report("sorting")));
    result.timings.push_back({"sort", watch.lap()});

    const GridNeighbors grid(g.dims[0], g.dims[1], g.dims[2]);
    if (faulting.joinable()) {
        faulting.join();
        if (fault_error)
            std::rethrow_exception(fault_error);
    } else {
        fault_in();
    }
    result.timings.push_back({"memory", watch.lap()});
    if (parallel) {
        std::exception_ptr split_error;
        std::thread split_thread([&] {
            try {
                compute_split_tree(grid, order, state.data(), split_components.data(), poll);
            } catch (...) {
                split_error = std::current_exception();
            }
        });
        try {
            compute_join_tree(grid, order, state.data(), labels.data(), report("join and split trees"));
        } catch (...) {
            split_thread.join();
            throw;
        }
        split_thread.join();
        if (split_error)
            std::rethrow_exception(split_error);
        split_components.release();
    } else {
        const ProgressFn join_progress = report("join tree"), split_progress = report("split tree");
        compute_join_tree(grid, order, state.data(), labels.data(), join_progress);
        compute_split_tree(grid, order, state.data(), labels.data(), split_progress);
    }
    result.timings.push_back({"join+split trees", watch.lap()});

    result.tree = merge_contour_tree(std::move(state), std::move(labels), std::move(order), report("merging trees"));
    result.timings.push_back({"merge", watch.lap()});

    result.total_seconds = total.lap();
    return result;
}

void decompose(TopologyResult &result, const Volume &volume, const ImportanceFn &importance,
               const StageProgressFn &progress, std::stop_token stop)
{
    Stopwatch watch;
    const FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                          &volume.geometry()};
    const ProgressFn report = [&progress, &stop](double f) {
        throw_if_stopped(stop);
        if (progress)
            progress("branches and measures", f);
    };
    result.branches = decompose_branches(result.tree, field, importance, report);
    const double seconds = watch.lap();
    result.timings.push_back({"branches+measures", seconds});
    result.total_seconds += seconds;
}

TopologyResult compute_topology(const Volume &volume, const ImportanceFn &importance,
                                const StageProgressFn &progress, std::stop_token stop, uint64_t memory_budget)
{
    TopologyResult result = compute_contour_tree(volume, progress, stop, memory_budget);
    decompose(result, volume, importance, progress, stop);
    return result;
}

} // namespace arbor::topology
