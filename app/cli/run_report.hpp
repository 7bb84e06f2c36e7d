// run_report.hpp - the report of `arbor run`: the input, every plugin with
// its version and parameters, the cut, per-stage seconds, how often each
// stage ran, and per branch its opacity and colour, as JSON (for machines)
// and Markdown (for people); with the session file, enough to reproduce the
// image.  One run: "arbor-run-report/1".  A sweep: "arbor-sweep-report/1",
// the same per run under "runs", plus the contact sheet.
#pragma once

#include "pipeline/pipeline.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace arbor::cli {

// One rendered image and what made it.
struct RenderedRun {
    std::string name, caption; // of the sweep point ("" for a single run)
    pipeline::Document document; // resolved, as rendered
    std::shared_ptr<const pipeline::CutResult> cut;
    std::shared_ptr<const pipeline::TransferFunctionsResult> tf;
    std::shared_ptr<const pipeline::RenderResult> render;
    std::shared_ptr<const pipeline::LegendResult> legend;
    std::filesystem::path image, legend_image;
    double coverage = 0.0; // fraction of the image covered
    double write_seconds = 0.0;
};

struct RunReport {
    std::shared_ptr<const pipeline::ImportResult> import;
    std::shared_ptr<const pipeline::FilterResult> filtered;
    std::shared_ptr<const pipeline::ContourTreeResult> tree;
    std::vector<RenderedRun> runs;
    std::array<uint64_t, pipeline::kStageCount> stage_runs{};
    std::filesystem::path contact_sheet, session, labels; // empty when not written
    std::string provenance; // the "provenance" object as JSON text (provenance.hpp)
};

// A label's share of the image's visibility (0 when nothing is visible).
double visibility_share(const RenderedImage &image, uint32_t label);

// Writes `path` (JSON) and the same name with .md.
void write_run_report(const std::filesystem::path &path, const RunReport &report);

} // namespace arbor::cli
