// stage_results.hpp - what each stage computes.  Results are immutable
// snapshots shared as std::shared_ptr<const T>: a front (the workstation's
// UI thread) may read one while the next job runs, and a result holds the
// upstream results it points into, so it stays valid on its own.
#pragma once

#include "auto_denoise.hpp"
#include "document.hpp"
#include "framing.hpp"
#include "stage_graph.hpp"
#include "viewpoint.hpp"
#include "visibility_balance.hpp"

#include "core/background_level.hpp"
#include "core/body_region.hpp"
#include "core/hounsfield_scale.hpp"
#include "core/volume.hpp"
#include "host/branch_tree_record.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"
#include "topology/importance_knee.hpp"
#include "topology/label_thickness.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace arbor::pipeline {

struct ImportResult {
    std::shared_ptr<const Volume> volume;
    std::string source;    // the path, or "phantom:head"
    PluginSetting importer; // as used: the values read back after the import (empty for phantoms)
    std::string checksum;   // of the voxels and grid (volume_checksum.hpp)
    // Set when the file named no unit and the values are those of a CT in
    // Hounsfield units: the volume's mapping then says "HU".
    std::optional<HounsfieldEvidence> hounsfield_inferred;
    double seconds = 0.0;
};

struct FilterResult {
    std::shared_ptr<const Volume> volume; // the import's own when the chain is empty
    std::optional<BackgroundLevel> background; // the values that are background (core/background_level.hpp)
    std::shared_ptr<const BodyRegion> body;    // where the body is (core/body_region.hpp)
    std::string source;                   // "scan.nrrd | gaussian:sigma=1.5"
    std::vector<PluginSetting> filters;   // as applied
    std::optional<DenoiseAdvice> denoise; // when the document asked for automatic denoising
    uint64_t revision = 0;                // unique per computed volume (renderers cache on it)
    double seconds = 0.0;
};

struct ContourTreeResult {
    topology::ContourTree tree;
    std::vector<topology::StageTiming> timings;
    double seconds = 0.0;
    bool from_cache = false;
    std::string memory_plan; // how its work space was laid out (topology_pipeline.hpp); "" from the cache
};

struct DecompositionResult {
    PluginSetting simplifier;
    std::string simplifier_name;
    topology::BranchDecomposition branches;
    double seconds = 0.0;
};

struct CutResult {
    std::shared_ptr<const DecompositionResult> decomposition;
    CutChoice requested;
    std::optional<topology::KneeChoice> knee; // set when the count came from the knee
    std::size_t background_branches = 0;      // left out as the background's basins and bumps
    std::size_t speck_branches = 0;           // left out of the knee's choice as too small to be seen
    topology::SimplificationCut cut;
    // Per voxel its kept label, and per label the thickness of its voxels.
    std::shared_ptr<const LabelMap> labels;
    std::vector<topology::LabelShape> shapes;
    // The kept branches as the record depictors and generators read (with
    // the thickness column); branch k of it is label k.
    std::unique_ptr<const BranchTreeRecord> tree;
    double seconds = 0.0;

    std::size_t kept() const { return cut.kept.size(); }
    // The cut as it was made ("keep 12" also for the knee's choice).
    CutChoice effective() const;
};

struct LabelsResult {
    explicit LabelsResult(std::shared_ptr<const CutResult> from) : cut(std::move(from)), labels(*cut->labels) {}
    std::shared_ptr<const CutResult> cut;
    const LabelMap &labels;         // per voxel: the kept label (the cut's)
    std::vector<std::string> names; // per label: "root", "max-<branch>", "min-<branch>"
    uint64_t revision = 0;
    double seconds = 0.0;
};

struct DepictionResult {
    std::shared_ptr<const CutResult> cut;
    PluginSetting depictor;             // empty: none depicted (neutral record)
    arbor_depiction_request request{};  // the selection the depictor saw
    std::unique_ptr<const DepictionRecord> depiction;
    double seconds = 0.0;
};

struct TransferFunctionsResult {
    std::shared_ptr<const DepictionResult> depiction;
    PluginSetting generator;               // empty when read from a file
    std::filesystem::path file;            // the file they came from, if any
    std::shared_ptr<const TransferFunctions> functions;
    // When the generator's flow rate Q is not its default Q0: the functions
    // at Q0, where the visibility balance is taken (flow_peel.hpp), and
    // Q / Q0.  Null and 1 otherwise: `functions` are those.
    std::shared_ptr<const TransferFunctions> reference;
    double flow_ratio = 1.0;
    const TransferFunctions &balanced_at() const { return reference ? *reference : *functions; }
    std::array<double, 2> value_range{};   // the volume's stored minimum and maximum
    double seconds = 0.0;
};

struct RenderResult {
    PluginSetting renderer;
    arbor_camera camera{}; // as rendered: framed, when the view asks for it
    RenderedImage image;
    // The transfer functions rendered: the generator's, or balanced.
    std::shared_ptr<const TransferFunctions> functions;
    std::optional<BalanceResult> balance; // taken at the default flow rate
    // Per branch, the flow rate's peel on top of the balance (flow_peel.hpp);
    // empty at the default flow rate or without a balance.
    std::vector<double> peel;
    std::optional<Framing> framing;
    std::optional<ViewpointChoice> viewpoint; // when the view was chosen
    double seconds = 0.0;
};

struct LegendResult {
    PluginSetting depictor;
    uint32_t selected = 0; // the branch the wheel is drawn around
    uint32_t size = 0;
    std::vector<float> rgba; // size x size, premultiplied, row 0 at the top
    double seconds = 0.0;
};

// The result type of each stage.
template <Stage S> struct StageResultOf;
template <> struct StageResultOf<Stage::Import> { using type = ImportResult; };
template <> struct StageResultOf<Stage::Filter> { using type = FilterResult; };
template <> struct StageResultOf<Stage::ContourTree> { using type = ContourTreeResult; };
template <> struct StageResultOf<Stage::Decomposition> { using type = DecompositionResult; };
template <> struct StageResultOf<Stage::Cut> { using type = CutResult; };
template <> struct StageResultOf<Stage::Labels> { using type = LabelsResult; };
template <> struct StageResultOf<Stage::Depiction> { using type = DepictionResult; };
template <> struct StageResultOf<Stage::TransferFunctions> { using type = TransferFunctionsResult; };
template <> struct StageResultOf<Stage::Render> { using type = RenderResult; };
template <> struct StageResultOf<Stage::Legend> { using type = LegendResult; };
template <Stage S> using StageResult = typename StageResultOf<S>::type;

} // namespace arbor::pipeline
