// study_figures.hpp - the figures of a comparison study, each as a PNG (at
// the DPI asked for) with an SVG twin:
//   priority-lines[-FILTER].png  the thesis' priority line window (Appendix
//        A) on a log scale: one row per simplifier, the first simplifier's
//        branches along x in a fixed order, each row's cut as a labelled line
//   dice-STRUCTURE.png  Dice against the cut for one truth structure, a line
//        per simplifier, a panel per filter setting
//   labels-AXIS.png  the volume's slice, the ground truth and every
//        simplifier's kept regions at the first filter and cut, in colours
//        that agree across panels (a region matched to a truth structure
//        takes its colour; one that is the same structure as a region of the
//        first simplifier takes that one's)
#pragma once

#include "study_run.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace arbor::cli {

enum class SliceAxis { Axial, Coronal, Sagittal };

struct FigureOptions {
    double dpi = 150;
    SliceAxis axis = SliceAxis::Axial;
    std::optional<int64_t> slice; // default: most truth voxels, else the middle
    std::size_t max_priority_columns = 600;
};

// Writes every figure into `dir`; returns their file names (PNG and SVG).
std::vector<std::string> write_study_figures(const std::filesystem::path &dir, const StudyOutcome &study,
                                             const FigureOptions &options);

} // namespace arbor::cli
