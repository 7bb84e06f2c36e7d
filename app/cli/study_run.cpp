#include "study_run.hpp"

#include "command_pipeline.hpp"

#include "io/color_table.hpp"
#include "io/label_map_output.hpp"
#include "pipeline/branch_importance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

namespace arbor::cli {

using pipeline::Stage;

namespace {

TreePoint tree_point(const topology::ContourTree &tree, const Volume &volume, uint32_t node)
{
    TreePoint p;
    const Geometry &g = volume.geometry();
    p.node = node;
    p.vertex = tree.node_vertex[node];
    p.ijk = {p.vertex % g.dims[0], (p.vertex / g.dims[0]) % g.dims[1], p.vertex / (g.dims[0] * g.dims[1])};
    p.position_mm = g.position_of(p.vertex);
    p.value = volume.value(p.vertex);
    return p;
}

std::vector<KeptRecord> kept_records(const topology::ContourTree &tree, const Volume &volume,
                                     const topology::BranchDecomposition &d, const topology::SimplificationCut &cut)
{
    std::vector<KeptRecord> out;
    for (std::size_t k = 0; k < cut.kept.size(); ++k) {
        const uint32_t b = cut.kept[k];
        const topology::Branch &br = d.branches[b];
        KeptRecord r;
        r.label = static_cast<uint32_t>(k);
        r.branch = b;
        r.parent_label = cut.kept_parent[k];
        r.depth = k == 0 ? 0 : out[static_cast<std::size_t>(cut.kept_parent[k])].depth + 1; // parents come first
        r.kind = br.kind;
        r.importance = std::isinf(br.importance) ? 1.0 : br.importance;
        r.extremum = tree_point(tree, volume, br.extremum_node);
        r.saddle = tree_point(tree, volume, br.saddle_node);
        r.measures = br.measures;
        for (int m = 0; m < topology::kMeasureCount; ++m)
            r.relative[static_cast<std::size_t>(m)] = d.relative(b, m);
        out.push_back(r);
    }
    return out;
}

// The level a cut corresponds to in its own importance.
double cut_level(const pipeline::CutResult &cut)
{
    if (cut.requested.threshold)
        return *cut.requested.threshold;
    const topology::BranchDecomposition &d = cut.decomposition->branches;
    double level = 0.0;
    for (std::size_t b = 1; b < d.branches.size(); ++b)
        if (cut.cut.kept_index[b] < 0)
            level = std::max(level, d.branches[b].importance);
    return level;
}

} // namespace

const char *scoring_name(RegionScoring s) { return s == RegionScoring::Subtree ? "subtree" : "exclusive"; }

GroundTruth load_ground_truth(Context &context, const std::string &path, const std::string &colours,
                              const std::array<int64_t, 3> &dims)
{
    CommandPipeline p(context, false);
    pipeline::Document d = pipeline::default_document();
    d.input.path = path;
    p->set_document(d);
    const auto truth = p.run<Stage::Import>()->volume;
    if (truth->geometry().dims != dims)
        throw std::invalid_argument(path + ": the ground truth's dims differ from the volume's");
    GroundTruth out;
    out.source = path;
    out.labels = std::make_shared<const study::TruthLabels>(study::read_truth(*truth));
    std::filesystem::path table_path = colours;
    if (table_path.empty() && std::filesystem::exists(io::color_table_path(path)))
        table_path = io::color_table_path(path);
    const auto table =
        table_path.empty() ? std::map<uint32_t, io::ColorTableEntry>{} : io::read_color_table(table_path);
    for (std::size_t t = 0; t < out.labels->labels.size(); ++t) {
        TruthStructure s;
        s.label = out.labels->labels[t];
        s.voxels = out.labels->voxels[t];
        const auto it = table.find(s.label);
        s.name = it != table.end() ? it->second.name : "label " + std::to_string(s.label);
        s.colour = it != table.end() ? it->second.colour : io::label_color(s.label);
        out.structures.push_back(s);
    }
    return out;
}

study::TruthMatches score_cut(const study::TruthLabels &truth, const pipeline::CutResult &cut, RegionScoring scoring)
{
    const study::Contingency exclusive = study::count_overlaps(truth, *cut.labels, cut.cut.kept.size());
    if (scoring == RegionScoring::Subtree)
        return study::match_regions(study::subtree_regions(exclusive, cut.cut.kept_parent), truth);
    return study::match_regions(exclusive, truth);
}

StudyOutcome run_study(pipeline::Pipeline &p, Context &context, const StudyRequest &request)
{
    StudyOutcome out;
    out.grid = request.grid;
    out.scoring = request.scoring;
    pipeline::Document d = p.document();
    const auto imported = p.run<Stage::Import>();
    out.input = imported->source;
    out.geometry = imported->volume->geometry();
    if (!request.truth_path.empty()) {
        GroundTruth truth =
            load_ground_truth(context, request.truth_path, request.truth_colors_path, out.geometry.dims);
        out.truth_source = truth.source;
        out.truth = std::move(truth.structures);
        out.truth_labels = std::move(truth.labels);
    }

    const pipeline::PluginCatalog &catalog = p.catalog();
    // The panels show the cut that keeps the most: the largest keep, or the
    // lowest threshold.
    std::size_t panel_cut = 0;
    for (std::size_t c = 1; c < request.grid.cuts.size(); ++c) {
        const pipeline::CutChoice &a = request.grid.cuts[c], &b = request.grid.cuts[panel_cut];
        if (a.keep && b.keep ? *a.keep > *b.keep : (a.threshold && b.threshold && *a.threshold < *b.threshold))
            panel_cut = c;
    }
    out.panels.cut = panel_cut;
    for (std::size_t f = 0; f < request.grid.filters.size(); ++f) {
        const StudyFilter &filter = request.grid.filters[f];
        d.filters = filter.chain;
        d.auto_denoise = false;
        d.simplifier = request.grid.simplifiers.front().setting;
        d.cut = request.grid.cuts.front();
        p.set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        const auto tree = p.run<Stage::ContourTree>();
        FilterOutcome fo;
        fo.filter = {filtered->filters, filter.label};
        fo.source = filtered->source;
        fo.nodes = tree->tree.node_count();
        fo.arcs = tree->tree.arc_count();
        fo.tree_seconds = tree->seconds;
        fo.filter_seconds = filtered->seconds;
        fo.tree_from_cache = tree->from_cache;
        std::printf("%s: contour tree of %zu nodes in %.2f s%s\n", fo.source.c_str(), fo.nodes, fo.tree_seconds,
                    fo.tree_from_cache ? " (cached)" : "");

        // Per simplifier its decomposition and the kept branches of every
        // cut (by branch), for the overlaps once all are made.
        std::vector<std::shared_ptr<const pipeline::DecompositionResult>> decompositions;
        std::vector<std::vector<std::vector<uint32_t>>> cuts;
        for (const StudySimplifier &s : request.grid.simplifiers) {
            p.set_simplifier(s.setting);
            SimplifierOutcome so;
            std::vector<std::vector<uint32_t>> made;
            for (const pipeline::CutChoice &choice : request.grid.cuts) {
                p.set_cut(choice);
                const auto cut = p.run<Stage::Cut>();
                if (so.cuts.empty()) {
                    so.simplifier = {cut->decomposition->simplifier, s.label};
                    so.name = cut->decomposition->simplifier_name;
                    so.version = cut->decomposition->simplifier.version;
                    so.branches = cut->decomposition->branches.branches.size();
                    so.seconds = cut->decomposition->seconds;
                    decompositions.push_back(cut->decomposition);
                }
                CutOutcome co;
                co.cut = choice;
                co.kept = kept_records(tree->tree, *filtered->volume, cut->decomposition->branches, cut->cut);
                co.level = cut_level(*cut);
                co.seconds = cut->seconds;
                if (out.truth_labels)
                    co.scores = score_cut(*out.truth_labels, *cut, out.scoring);
                if (f == 0 && so.cuts.size() == panel_cut) {
                    out.panels.volume = filtered->volume;
                    out.panels.labels.push_back(cut->labels);
                    out.panels.kept.push_back(co.kept);
                }
                made.push_back(cut->cut.kept);
                so.cuts.push_back(std::move(co));
            }
            std::printf("  %-40s %8zu branches, kept %s, %.2f s\n", s.label.c_str(), so.branches,
                        [&] {
                            std::string k;
                            for (const CutOutcome &c : so.cuts)
                                k += (k.empty() ? "" : ",") + std::to_string(c.kept.size());
                            return k;
                        }()
                            .c_str(),
                        so.seconds);
            std::fflush(stdout);
            cuts.push_back(std::move(made));
            fo.simplifiers.push_back(std::move(so));
        }
        for (std::size_t c = 0; c < request.grid.cuts.size(); ++c)
            for (std::size_t a = 0; a < decompositions.size(); ++a)
                for (std::size_t b = a + 1; b < decompositions.size(); ++b)
                    fo.overlaps.push_back({c, a, b,
                                           study::kept_overlap(decompositions[a]->branches, cuts[a][c],
                                                               decompositions[b]->branches, cuts[b][c])});
        for (const auto &decomposition : decompositions)
            fo.priorities.push_back(
                pipeline::branch_importance(catalog, decomposition->simplifier, decompositions.front()->branches,
                                            filtered->volume->mapping()));
        out.filters.push_back(std::move(fo));
    }
    return out;
}

} // namespace arbor::cli
