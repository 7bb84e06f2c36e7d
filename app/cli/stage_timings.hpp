// stage_timings.hpp - `--timings` of the topology commands: seconds per
// stage of the contour tree (or the cache read that replaced it) and of the
// branch decomposition, peak memory per voxel, and the tree's size, on stderr.
#pragma once

#include "pipeline/stage_results.hpp"

namespace arbor::cli {

void print_timings(const pipeline::ContourTreeResult &tree, const pipeline::DecompositionResult *decomposition,
                   const Volume &volume);

} // namespace arbor::cli
