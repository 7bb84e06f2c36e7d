#include "stage_timings.hpp"

#include "core/resident_memory.hpp"
#include "core/volume_header.hpp"

#include <cstdio>

namespace arbor::cli {

void print_timings(const pipeline::ContourTreeResult &tree, const pipeline::DecompositionResult *decomposition,
                   const Volume &volume)
{
    const double n = static_cast<double>(volume.voxel_count());
    double total = 0;
    for (const topology::StageTiming &t : tree.timings) {
        std::fprintf(stderr, "  %-20s %8.3f s\n", t.stage.c_str(), t.seconds);
        total += t.seconds;
    }
    if (decomposition) {
        std::fprintf(stderr, "  %-20s %8.3f s\n", "branches+measures", decomposition->seconds);
        total += decomposition->seconds;
    }
    std::fprintf(stderr, "  %-20s %8.3f s%s\n", "total", total,
                 tree.from_cache ? " (the tree came from the on-disk cache; --no-cache to time building it)" : "");
    const uint64_t peak = peak_resident_bytes();
    std::fprintf(stderr, "  %-20s %s (%.1f bytes/voxel, input %u bytes/voxel)\n", "peak memory",
                 format_bytes(peak).c_str(), static_cast<double>(peak) / n, arbor_voxel_size(volume.type()));
    std::fprintf(stderr, "  %-20s %zu nodes, %zu arcs", "contour tree", tree.tree.node_count(), tree.tree.arc_count());
    if (decomposition)
        std::fprintf(stderr, ", %zu branches", decomposition->branches.branches.size());
    std::fprintf(stderr, "\n");
}

} // namespace arbor::cli
