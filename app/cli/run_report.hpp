// run_report.hpp - the report of `arbor run`: inputs, every plugin with its
// version and parameters, per-stage seconds, branch counts before and after
// simplification, and per branch its opacity and colour, as JSON (for
// machines) and Markdown (for people), enough to reproduce the image.
#pragma once

#include "simplification_run.hpp"
#include "transfer_function_stage.hpp"

#include "host/rendering.hpp"
#include "topology/importance_knee.hpp"
#include "topology/topology_pipeline.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace arbor::cli {

struct RunReport {
    std::vector<std::pair<std::string, double>> stages; // name, seconds
    void stage(const std::string &name, double seconds) { stages.emplace_back(name, seconds); }

    std::string source, importer;
    const PluginInstance *filter = nullptr;
    const Volume *volume = nullptr;
    const topology::TopologyResult *topology = nullptr;
    const SimplifiedTree *simplified = nullptr;
    CutRequest cut;
    std::optional<topology::KneeChoice> knee; // set when the count came from the knee
    const arbor_branch_tree *tree = nullptr;
    const TransferFunctionResult *tf = nullptr;
    const PluginInstance *renderer = nullptr;
    Orbit orbit;
    uint32_t width = 0, height = 0;
    double coverage = 0.0;
    std::string image, legend;
    uint32_t legend_selected = 0;
};

// Writes `path` (JSON) and the same name with .md.
void write_run_report(const std::filesystem::path &path, const RunReport &r);

} // namespace arbor::cli
