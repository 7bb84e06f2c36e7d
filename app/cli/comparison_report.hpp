// comparison_report.hpp - the report of `arbor compare`: report.json (all
// of it, machine-readable), report.csv (one row per kept branch per
// simplifier) and report.md (for people: summary, overlaps, Dice, the
// images).
#pragma once

#include "comparison.hpp"

#include "pipeline/document.hpp"
#include "pipeline/stage_results.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace arbor::cli {

struct ComparisonStudy {
    std::string source;
    const Volume *volume = nullptr;
    const pipeline::ContourTreeResult *tree = nullptr;
    pipeline::CutChoice request;
    std::vector<ComparedSimplifier> runs;
    std::vector<Overlap> overlaps;
    std::string truth_source; // empty: no ground truth
    std::vector<TruthScore> truth;
    std::vector<std::string> images; // file names in the output folder
};

void write_report_json(const std::filesystem::path &path, const ComparisonStudy &study);
void write_report_csv(const std::filesystem::path &path, const ComparisonStudy &study);
void write_report_markdown(const std::filesystem::path &path, const ComparisonStudy &study);

} // namespace arbor::cli
