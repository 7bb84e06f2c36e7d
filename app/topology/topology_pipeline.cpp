#include "topology_pipeline.hpp"

#include "core/cancelled.hpp"
#include "core/stopwatch.hpp"

#include "grid_neighbors.hpp"
#include "merge_tree.hpp"
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

TopologyResult compute_contour_tree(const Volume &volume, const StageProgressFn &progress, std::stop_token stop)
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

    UninitializedBuffer<uint32_t> order = sort_vertices(volume.type(), volume.data(), n, report("sorting"));
    result.timings.push_back({"sort", watch.lap()});

    // The two sweeps are independent: run the split tree on a second thread.
    const GridNeighbors grid(g.dims[0], g.dims[1], g.dims[2]);
    // One block serves the sweeps' components (4 + 4 bytes a vertex) and then
    // the merge's state (16): memory touched for the first time costs more
    // than the sweeps' arithmetic on a virtual machine, so it is touched once.
    static_assert(2 * kSweepScratchBytes <= kMergeWorkBytes);
    UninitializedBuffer<uint8_t> work(std::size_t{n} * kMergeWorkBytes);
    uint32_t *const components = reinterpret_cast<uint32_t *>(work.data());
    const SweepScratch join_scratch{components};
    const SweepScratch split_scratch{components + n};
    MergeTree join, split;
    std::exception_ptr split_error;
    std::thread split_thread([&] {
        try {
            split = compute_split_tree(grid, order, poll, &split_scratch);
        } catch (...) {
            split_error = std::current_exception();
        }
    });
    try {
        join = compute_join_tree(grid, order, report("join and split trees"),
                                 &join_scratch);
    } catch (...) {
        split_thread.join();
        throw;
    }
    split_thread.join();
    if (split_error)
        std::rethrow_exception(split_error);
    result.timings.push_back({"join+split trees", watch.lap()});
    result.tree = merge_contour_tree(std::move(join), std::move(split), std::move(order), report("merging trees"),
                                     std::move(work));
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
                                const StageProgressFn &progress, std::stop_token stop)
{
    TopologyResult result = compute_contour_tree(volume, progress, stop);
    decompose(result, volume, importance, progress, stop);
    return result;
}

} // namespace arbor::topology
