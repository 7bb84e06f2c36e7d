// simplification_run.hpp - one simplifier applied to a contour tree: the
// branch decomposition its importance drives (the host's one pruning
// engine), cut at a threshold or at a branch count, and how the kept
// branches are written out.  Simplifiers compared on one volume share the
// tree; only the decomposition is redone per simplifier.
#pragma once

#include "cli_context.hpp"

#include "core/volume.hpp"
#include "io/json_writer.hpp"
#include "topology/simplification.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::cli {

struct CutRequest {
    std::optional<double> threshold; // keep branches with importance > threshold
    std::optional<std::size_t> keep; // or the N most important (root included)
    std::string describe() const;    // "keep 12" / "threshold 0.01"
    // The inverse of describe(); throws std::invalid_argument.
    static CutRequest parse(const std::string &text);
};

// --keep N | --threshold T on `command` (exclusive); `what` completes the
// threshold's help ("relative persistence").
void add_cut_options(CLI::App &command, CutRequest &cut, const std::string &threshold_help);

// "cut": {"keep": N} or {"threshold": T}.
void write_cut(io::JsonWriter &j, const CutRequest &cut);

struct SimplifiedTree {
    std::string id, name, version; // the simplifier plugin
    topology::BranchDecomposition branches;
    topology::SimplificationCut cut;
    double seconds = 0.0; // decomposition and cut
};

SimplifiedTree simplify_tree(const topology::ContourTree &tree, const Volume &volume, PluginInstance &simplifier,
                             const CutRequest &request, Context &context);

// Names of the kept branches, by label: "root", "max-<branch>", "min-<branch>".
std::vector<std::string> kept_label_names(const topology::BranchDecomposition &d,
                                          const topology::SimplificationCut &cut);

// Depth of every kept branch in the simplified hierarchy (root 0).
std::vector<uint32_t> kept_depths(const topology::SimplificationCut &cut);

// "id", "name", "version" of the simplifier that made `s` (fields of an
// object the caller opens).
void write_simplifier_fields(io::JsonWriter &j, const SimplifiedTree &s);

// key: an array with one object per kept branch: label, branch, parent
// label, kind, depth, importance, extremum and saddle points, measures
// absolute and relative.
void write_kept_branches(io::JsonWriter &j, std::string_view key, const topology::ContourTree &tree,
                         const Volume &volume, const SimplifiedTree &s);

} // namespace arbor::cli
