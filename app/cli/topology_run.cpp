#include "topology_run.hpp"

#include "core/resident_memory.hpp"
#include "core/volume_header.hpp"

#include <cstdio>

namespace arbor::cli {

namespace {

topology::StageProgressFn terminal_stages(Context &context)
{
    return [&context](const char *stage, double fraction) { context.progress.report(stage, fraction); };
}

} // namespace

topology::TopologyResult run_topology(const Volume &volume, const topology::ImportanceFn &importance,
                                      Context &context)
{
    Task task(&context.progress); // owns the progress display for the run
    return topology::compute_topology(volume, importance, terminal_stages(context), context.stop.get_token());
}

topology::TopologyResult run_contour_tree(const Volume &volume, Context &context)
{
    Task task(&context.progress);
    return topology::compute_contour_tree(volume, terminal_stages(context), context.stop.get_token());
}

void print_timings(const topology::TopologyResult &result, const Volume &volume)
{
    const double n = static_cast<double>(volume.voxel_count());
    for (const topology::StageTiming &t : result.timings)
        std::fprintf(stderr, "  %-20s %8.3f s\n", t.stage.c_str(), t.seconds);
    std::fprintf(stderr, "  %-20s %8.3f s\n", "total", result.total_seconds);
    const uint64_t peak = peak_resident_bytes();
    std::fprintf(stderr, "  %-20s %s (%.1f bytes/voxel, input %u bytes/voxel)\n", "peak memory",
                 format_bytes(peak).c_str(), static_cast<double>(peak) / n,
                 arbor_voxel_size(volume.type()));
    std::fprintf(stderr, "  %-20s %zu nodes, %zu arcs, %zu branches\n", "contour tree",
                 result.tree.node_count(), result.tree.arc_count(), result.branches.branches.size());
}

} // namespace arbor::cli
