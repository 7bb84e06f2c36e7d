// comparison_report.hpp - what `arbor compare` writes of a study:
//   report.json   everything, with the provenance that reproduces it and no
//                 timings (two runs of one study give the same bytes)
//   timings.json  the seconds each stage took
//   study.csv     tidy, one row per filter x cut x simplifier x truth
//                 structure (one per filter x cut x simplifier without a
//                 truth): the matched region, Dice, precision, recall
//   report.csv    one row per kept branch of every cut
//   report.md     for people: the settings, the scores, the figures
#pragma once

#include "study_run.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace arbor::io {
class JsonWriter;
}

namespace arbor::cli {

struct StudyReport {
    const StudyOutcome *study = nullptr;
    std::vector<std::string> figures;           // file names in the output folder
    std::function<void(io::JsonWriter &)> provenance; // writes the "provenance" member
};

void write_report_json(const std::filesystem::path &path, const StudyReport &report);
void write_timings_json(const std::filesystem::path &path, const StudyOutcome &study);
void write_study_csv(const std::filesystem::path &path, const StudyOutcome &study);
void write_kept_csv(const std::filesystem::path &path, const StudyOutcome &study);
void write_report_markdown(const std::filesystem::path &path, const StudyReport &report);

// "keep 16" / "threshold 0.05": the cut as the tables name it.
std::string cut_name(const pipeline::CutChoice &cut);

} // namespace arbor::cli
