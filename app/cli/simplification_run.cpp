#include "simplification_run.hpp"

#include "core/cancelled.hpp"
#include "host/simplifier_importance.hpp"
#include "io/topology_json.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

namespace arbor::cli {

std::string CutRequest::describe() const
{
    std::ostringstream s;
    if (keep)
        s << "keep " << *keep;
    else if (threshold)
        s << "threshold " << *threshold;
    else
        s << "no cut";
    return s.str();
}

CutRequest CutRequest::parse(const std::string &text)
{
    std::istringstream in(text);
    std::string word;
    double x = 0;
    CutRequest r;
    if (in >> word >> x && in.eof()) {
        if (word == "keep" && x >= 1 && x == std::floor(x)) {
            r.keep = static_cast<std::size_t>(x);
            return r;
        }
        if (word == "threshold" && x >= 0 && x <= 1) {
            r.threshold = x;
            return r;
        }
    }
    throw std::invalid_argument("'" + text + "' is not a cut (\"keep N\" or \"threshold T\")");
}

void add_cut_options(CLI::App &command, CutRequest &cut, const std::string &threshold_help)
{
    auto *keep = command.add_option("--keep", cut.keep, "Keep the N most important branches (root included)")
                     ->check(CLI::PositiveNumber);
    auto *threshold = command.add_option("--threshold", cut.threshold, threshold_help)->check(CLI::Range(0.0, 1.0));
    keep->excludes(threshold);
}

void write_cut(io::JsonWriter &j, const CutRequest &cut)
{
    const io::JsonWriter::Scope o = j.object("cut");
    if (cut.keep)
        j.field("keep", *cut.keep);
    else
        j.field("threshold", cut.threshold.value_or(0.0));
}

SimplifiedTree simplify_tree(const topology::ContourTree &tree, const Volume &volume, PluginInstance &simplifier,
                             const CutRequest &request, Context &context)
{
    const auto start = std::chrono::steady_clock::now();
    SimplifiedTree out;
    out.id = simplifier.id();
    out.name = simplifier.descriptor().name;
    out.version = simplifier.descriptor().version;
    const topology::ImportanceFn importance = simplifier_importance(simplifier);
    {
        Task task(&context.progress); // owns the progress display
        const topology::FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                                        &volume.geometry()};
        const std::string stage = "branches by " + out.id;
        out.branches = topology::decompose_branches(tree, field, importance, [&](double f) {
            throw_if_stopped(context.stop.get_token());
            context.progress.report(stage, f);
        });
    }
    if (request.keep)
        out.cut = topology::cut_by_count(out.branches, *request.keep);
    else
        out.cut = topology::cut_by_threshold(out.branches, request.threshold.value_or(0.0));
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::vector<std::string> kept_label_names(const topology::BranchDecomposition &d,
                                          const topology::SimplificationCut &cut)
{
    std::vector<std::string> names;
    names.reserve(cut.kept.size());
    for (const uint32_t b : cut.kept) {
        const topology::BranchKind k = d.branches[b].kind;
        names.push_back(k == topology::BranchKind::Root ? std::string("root")
                                                         : (k == topology::BranchKind::Maximum ? "max-" : "min-") +
                                                               std::to_string(b));
    }
    return names;
}

std::vector<uint32_t> kept_depths(const topology::SimplificationCut &cut)
{
    std::vector<uint32_t> depth(cut.kept.size(), 0);
    for (std::size_t k = 1; k < cut.kept.size(); ++k)
        depth[k] = depth[static_cast<std::size_t>(cut.kept_parent[k])] + 1; // parents come first
    return depth;
}

void write_simplifier_fields(io::JsonWriter &j, const SimplifiedTree &s)
{
    j.field("id", s.id);
    j.field("name", s.name);
    j.field("version", s.version);
}

void write_kept_branches(io::JsonWriter &j, std::string_view key, const topology::ContourTree &tree,
                         const Volume &volume, const SimplifiedTree &s)
{
    const topology::BranchDecomposition &d = s.branches;
    const std::vector<uint32_t> depth = kept_depths(s.cut);
    const io::JsonWriter::Scope kept = j.array(key);
    for (std::size_t k = 0; k < s.cut.kept.size(); ++k) {
        const uint32_t b = s.cut.kept[k];
        const topology::Branch &br = d.branches[b];
        const io::JsonWriter::Scope o = j.object();
        j.field("label", k);
        j.field("branch", b);
        j.field("parent_label", s.cut.kept_parent[k]);
        j.field("kind", io::branch_kind_name(br.kind));
        j.field("depth", depth[k]);
        j.field("importance", std::isinf(br.importance) ? 1.0 : br.importance);
        io::write_branch_ends_and_measures(j, tree, volume, d, b);
    }
}

} // namespace arbor::cli
