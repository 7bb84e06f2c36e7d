// document.hpp - the user's choices a pipeline computes from: the input, the
// filter chain, every plugin with all its parameter values, the cut, the
// selection and the view.  Plain values, copyable and comparable: a session
// file is a document written out, a workstation's undo stack is a list of
// them, and every job works on the copy taken when it was requested.
//
// The choices fall into groups (stage_graph.hpp).  The pipeline keeps one
// revision per group and a stage depends on some groups, so changing a
// choice re-runs exactly the stages downstream of its group.
#pragma once

#include "host/rendering.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace arbor::pipeline {

// A plugin and its parameter values as text (host/param_text.hpp: "1.5",
// "64,64,64", "hat", "true").  As a front gives it, `id` may be the last
// part of the id ("itri") and `params` only what the user set; resolved by
// the pipeline (PluginCatalog::resolve), it holds the full id, the plugin's
// version and every parameter's value, each checked against its description.
struct PluginSetting {
    std::string id;
    std::string version;
    std::map<std::string, std::string> params;

    bool empty() const { return id.empty(); }
    bool operator==(const PluginSetting &) const = default;
};

// "gaussian:sigma=1.5" -> {id "gaussian", params {sigma: "1.5"}}, the form
// --filter and the workstation's `set filter` take; `what` names the text
// in messages ("--filter").  Throws std::invalid_argument.
PluginSetting parse_plugin_spec(const std::string &spec, const std::string &what);

// The built-in synthetic head (core/phantom.hpp), the data that needs no file.
struct PhantomInput {
    std::string kind = "head";
    int64_t size = 128;
    double noise = 0.0;
    int blobs = 0;
    uint64_t seed = 1;
    bool operator==(const PhantomInput &) const = default;
};

struct InputChoice {
    // A volume file, a DICOM file or folder, or a URI such as
    // pacs://NODE/SERIES_UID that PipelineOptions::fetch_input resolves.
    std::filesystem::path path;
    std::optional<PhantomInput> phantom; // instead of a path
    // Empty id: chosen by probing the file (its params still apply, e.g.
    // "series" for a DICOM folder).
    PluginSetting importer;

    bool empty() const { return path.empty() && !phantom; }
    bool operator==(const InputChoice &) const = default;
};

// "scheme://...": an input the pipeline fetches, kept as written (not a path
// to make absolute or relative).
bool is_input_uri(const std::string &text);

// Where the branch hierarchy is cut: the N most important branches (root
// included), those whose importance exceeds a threshold, or neither: the
// knee of the importance curve (topology/importance_knee.hpp).
struct CutChoice {
    std::optional<std::size_t> keep;
    std::optional<double> threshold;
    // Keep basins and bumps that lie wholly in the background's values (the
    // noise in the air) as structures; by default they are left out.
    bool keep_background = false;

    bool automatic() const { return !keep && !threshold; }
    std::string describe() const; // "keep 12", "threshold 0.01", "knee"
    // The inverse of describe(); throws std::invalid_argument.
    static CutChoice parse(const std::string &text);
    bool operator==(const CutChoice &) const = default;
};

// How the kept branches look: the relationship depicted, the selection, the
// transfer-function generator, and the relation-wheel legend.
struct Appearance {
    PluginSetting depictor;          // empty: no relationship depicted
    std::optional<int32_t> selected; // a label of the simplified tree
    PluginSetting generator;
    uint32_t lut_size = 256;
    // Instead of the generator: transfer functions read from this file
    // (arbor-transfer-functions/1, e.g. edited after `arbor tf`).
    std::filesystem::path transfer_functions_file;
    // The legend: this depictor's drawing around the selected branch (or the
    // deepest one).  Empty: none.
    PluginSetting legend;
    uint32_t legend_size = 512;
    // Scale each branch's opacity until the picture gives every structure
    // its share (visibility_balance.hpp).
    bool balance_visibility = true;

    bool operator==(const Appearance &) const = default;
};

// A person's edit of one structure's look in the 3D view: shown or not,
// its opacity (a multiplier of its optical depth: 2 is as if twice as
// dense) and its colour.  Applied on top of the transfer functions (and
// their balance) when rendering, so they survive a new flow rate, shape
// or cut until reset.
struct BranchStyle {
    bool visible = true;
    double opacity = 1.0;                        // >= 0
    std::optional<std::array<double, 3>> color;  // sRGB in [0, 1]; none: the generator's
    bool operator==(const BranchStyle &) const = default;
};

struct ViewChoice {
    Orbit orbit;
    // Frame what is visible (framing.hpp) rather than the grid's box; the
    // orbit's zoom applies on top.
    bool frame_content = true;
    // Choose the orbit's azimuth and elevation from the structures
    // (viewpoint.hpp) instead of taking them from `orbit`.
    bool auto_view = false;
    uint32_t width = 512, height = 512;
    std::array<double, 4> background{0.0, 0.0, 0.0, 1.0};
    PluginSetting renderer;
    // By the branch's extremum vertex (what identifies a branch across
    // cuts and simplifiers, arbor_branch_tree.extremum_vertex).
    std::map<int64_t, BranchStyle> branch_styles;
    bool operator==(const ViewChoice &) const = default;
};

struct Document {
    InputChoice input;
    std::vector<PluginSetting> filters;
    // With no filters given: denoise when the scan is dominated by noise, as
    // `arbor denoise-study` would suggest (auto_denoise.hpp).
    bool auto_denoise = true;
    PluginSetting simplifier;
    CutChoice cut;
    Appearance appearance;
    ViewChoice view;
    bool operator==(const Document &) const = default;
};

// What a new session starts with: no input yet, no filter, ITri cut at the
// knee, the inclusion relationship, residue-flow transfer functions, the
// neighbour relation wheel as the legend, the CPU ray caster.
Document default_document();

} // namespace arbor::pipeline
