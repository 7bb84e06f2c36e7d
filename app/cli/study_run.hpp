// study_run.hpp - a comparison study run on the pipeline: for every filter
// chain the contour tree once, for every simplifier setting its
// decomposition once, and every cut of it, scored against the ground truth
// as it is made; label maps are let go once scored (only the panels' stay),
// so a sweep of hundreds of cuts needs no more memory than one.
#pragma once

#include "cli_context.hpp"
#include "study_grid.hpp"

#include "core/label_map.hpp"
#include "io/label_colors.hpp"
#include "pipeline/pipeline.hpp"
#include "study/kept_overlap.hpp"
#include "study/region_scores.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace arbor::cli {

// A point of the tree: what the report says of a kept branch's ends.
struct TreePoint {
    uint32_t node = 0, vertex = 0;
    std::array<int64_t, 3> ijk{};
    std::array<double, 3> position_mm{};
    double value = 0.0;
};

struct KeptRecord {
    uint32_t label = 0, branch = 0, depth = 0;
    int32_t parent_label = -1;
    topology::BranchKind kind = topology::BranchKind::Root;
    double importance = 0.0; // 1 for the root
    TreePoint extremum, saddle;
    std::array<double, topology::kMeasureCount> measures{}, relative{};
};

struct CutOutcome {
    pipeline::CutChoice cut;
    std::vector<KeptRecord> kept;
    // The importance level the cut corresponds to: its threshold, or the
    // first importance a keep-N cut drops.
    double level = 0.0;
    std::optional<study::TruthMatches> scores;
    double seconds = 0.0;
};

struct SimplifierOutcome {
    StudySimplifier simplifier; // as resolved, with the parameters it ran with
    std::string name, version;
    std::size_t branches = 0;
    double seconds = 0.0; // the decomposition
    std::vector<CutOutcome> cuts; // one per grid cut
};

struct OverlapOutcome {
    std::size_t cut = 0, a = 0, b = 0; // indices into the grid's cuts and simplifiers
    study::KeptOverlap overlap;
};

struct FilterOutcome {
    StudyFilter filter;                  // as applied
    std::string source;                  // "scan.nrrd | gaussian:sigma=1"
    std::size_t nodes = 0, arcs = 0;
    double tree_seconds = 0.0, filter_seconds = 0.0;
    bool tree_from_cache = false;
    std::vector<SimplifierOutcome> simplifiers;
    std::vector<OverlapOutcome> overlaps;
    // Priority lines: per simplifier, its importance of the first
    // simplifier's branches (element b - 1 is branch b's), and the level of
    // its first cut.
    std::vector<std::vector<double>> priorities;
};

struct TruthStructure {
    uint32_t label = 0;
    std::string name;
    io::Rgb8 colour{};
    uint64_t voxels = 0;
};

// A ground truth read as any input is (through its importer), with the
// names and colours of its colour table: `colours`, or the .ctbl beside it.
struct GroundTruth {
    std::string source;
    std::vector<TruthStructure> structures;
    std::shared_ptr<const study::TruthLabels> labels;
};
// Throws std::invalid_argument when its dims are not `dims`.
GroundTruth load_ground_truth(Context &context, const std::string &path, const std::string &colours,
                              const std::array<int64_t, 3> &dims);

enum class RegionScoring { Exclusive, Subtree };
const char *scoring_name(RegionScoring s);

// The cut's kept regions matched to the truth's structures.
study::TruthMatches score_cut(const study::TruthLabels &truth, const pipeline::CutResult &cut, RegionScoring scoring);

// The label maps the panels show: the first filter at the cut that keeps
// the most branches.
struct PanelMaps {
    std::size_t cut = 0; // in the grid's cuts
    std::shared_ptr<const Volume> volume; // the first filter's volume
    std::vector<std::shared_ptr<const LabelMap>> labels; // per simplifier
    std::vector<std::vector<KeptRecord>> kept;           // per simplifier
};

struct StudyOutcome {
    std::string input;  // the source without filters
    Geometry geometry;
    StudyGrid grid;
    RegionScoring scoring = RegionScoring::Exclusive;
    std::string truth_source; // empty: no ground truth
    std::vector<TruthStructure> truth;
    std::shared_ptr<const study::TruthLabels> truth_labels;
    std::vector<FilterOutcome> filters;
    PanelMaps panels;
};

struct StudyRequest {
    StudyGrid grid;
    RegionScoring scoring = RegionScoring::Exclusive;
    std::string truth_path, truth_colors_path;
};

// Runs the study on `pipeline`, whose document holds the input; reports
// each setting on stdout as it is done.
StudyOutcome run_study(pipeline::Pipeline &pipeline, Context &context, const StudyRequest &request);

} // namespace arbor::cli
