// topology_run.hpp - what the topology commands (tree, pairs) share:
// running the pipeline with terminal progress, and printing per-stage
// timings and peak memory.
#pragma once

#include "cli_context.hpp"

#include "topology/topology_pipeline.hpp"

namespace arbor::cli {

topology::TopologyResult run_topology(const Volume &volume, const topology::ImportanceFn &importance,
                                      Context &context);

// The contour tree alone (no branches yet), with terminal progress.
topology::TopologyResult run_contour_tree(const Volume &volume, Context &context);

// Per-stage seconds, total, and peak memory (bytes per voxel) on stderr.
void print_timings(const topology::TopologyResult &result, const Volume &volume);

} // namespace arbor::cli
