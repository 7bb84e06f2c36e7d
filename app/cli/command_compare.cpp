// `arbor compare <volume> --simplifiers itri,persistence,volume,hypervolume
// --keep N --out DIR [--truth labels.nrrd]`: the comparison study.  The
// contour tree is computed once; every simplifier decomposes and cuts it
// with its own importance, so the runs differ in nothing else.
#include "commands.hpp"
#include "comparison_report.hpp"
#include "label_slices.hpp"
#include "priority_lines.hpp"
#include "plugin_choice.hpp"
#include "topology_run.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "host/simplifier_importance.hpp"
#include "host/volume_import.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numeric>
#include <set>

namespace arbor::cli {

namespace {

struct CompareArgs {
    VolumeInput input;
    FilterInput filter;
    PluginChoice simplifiers{ARBOR_KIND_SIMPLIFIER, "simplifier"};
    std::string list = "itri,persistence,volume,hypervolume";
    CutRequest cut;
    std::string out, truth;
};

constexpr std::size_t kMaxPriorityColumns = 600;

// One priority-line row per simplifier: its importance of the branches of
// the first simplifier's decomposition (so every row shows the same
// branches), and the level its own cut corresponds to.
std::vector<PriorityRow> priority_rows(const std::vector<ComparedSimplifier> &runs,
                                       const std::vector<PluginInstance *> &plugins, const CutRequest &request)
{
    const topology::BranchDecomposition &ref = runs[0].run.branches;
    const std::size_t n = ref.branches.size();
    std::vector<PriorityRow> rows;
    std::vector<topology::BranchMeasures> batch;
    std::vector<double> values;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const topology::ImportanceFn importance = simplifier_importance(*plugins[r]);
        PriorityRow row;
        row.name = runs[r].run.name;
        row.values.reserve(n > 0 ? n - 1 : 0);
        for (std::size_t start = 1; start < n; start += 4096) {
            batch.clear();
            for (std::size_t b = start; b < std::min(n, start + 4096); ++b) {
                topology::BranchMeasures m;
                m.absolute = ref.branches[b].measures;
                for (int c = 0; c < topology::kMeasureCount; ++c)
                    m.relative[static_cast<std::size_t>(c)] = ref.relative(static_cast<uint32_t>(b), c);
                batch.push_back(m);
            }
            importance(batch, values);
            row.values.insert(row.values.end(), values.begin(), values.end());
        }
        if (request.threshold) {
            row.threshold = *request.threshold;
        } else {
            // The first value a keep-N cut of this row would drop.
            std::vector<double> sorted = row.values;
            std::sort(sorted.begin(), sorted.end(), std::greater<>());
            const std::size_t kept = request.keep.value_or(1) - 1; // the root is not a column
            row.threshold = kept < sorted.size() ? sorted[kept] : 0.0;
        }
        rows.push_back(std::move(row));
    }
    // Columns: the most important branches of every row (so the kept ones and
    // those just below the line are all visible), in branch order.
    std::set<std::size_t> columns;
    const std::size_t per_row =
        std::max<std::size_t>(20, std::min(kMaxPriorityColumns / std::max<std::size_t>(rows.size(), 1),
                                           3 * request.keep.value_or(50)));
    for (const PriorityRow &row : rows) {
        std::vector<std::size_t> idx(row.values.size());
        std::iota(idx.begin(), idx.end(), std::size_t{0});
        const std::size_t take = std::min(per_row, idx.size());
        std::partial_sort(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(take), idx.end(),
                          [&](std::size_t a, std::size_t b) { return row.values[a] > row.values[b]; });
        columns.insert(idx.begin(), idx.begin() + static_cast<std::ptrdiff_t>(take));
    }
    for (PriorityRow &row : rows) {
        std::vector<double> shown;
        for (std::size_t c : columns)
            shown.push_back(row.values[c]);
        row.values = std::move(shown);
    }
    return rows;
}

Volume load_truth(const std::string &path, Context &context)
{
    PluginInstance importer = context.registry.create(choose_importer(context.registry, path));
    return import_volume(importer, path, &context.progress, context.max_volume_bytes, context.stop.get_token());
}

} // namespace

void add_compare_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "compare", "Compare simplifiers on one contour tree: kept branches, overlaps, Dice, priority lines");
    auto a = std::make_shared<CompareArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--simplifiers", a->list,
                    "Comma-separated simplifier plugins (ids or their last parts); the first one's branches are "
                    "the columns of the priority lines")
        ->default_val("itri,persistence,volume,hypervolume");
    add_cut_options(*sub, a->cut, "Instead of --keep: keep branches whose importance exceeds T");
    sub->add_option("--out", a->out, "Folder for report.json, report.csv, report.md and the PNGs")->required();
    sub->add_option("--truth", a->truth,
                    "Ground-truth label map with the volume's dims (any importable format): Dice per label");
    a->simplifiers.add_to(*sub, context, "Simplifier options");
    context.add_command(sub, [a, &context]() {
        if (!a->cut.keep && !a->cut.threshold)
            throw std::invalid_argument("give --keep N or --threshold T");
        std::vector<PluginInstance *> plugins;
        for (const std::string &name : split_names(a->list)) {
            PluginInstance *p = &a->simplifiers.resolve(name);
            if (std::find(plugins.begin(), plugins.end(), p) != plugins.end())
                throw std::invalid_argument("--simplifiers names " + p->id() + " twice");
            plugins.push_back(p);
        }
        if (plugins.empty())
            throw std::invalid_argument("--simplifiers is empty");
        LoadedVolume in = a->input.load();
        a->filter.apply(in, context);
        std::optional<Volume> truth;
        if (!a->truth.empty()) {
            truth = load_truth(a->truth, context);
            if (truth->geometry().dims != in.volume.geometry().dims)
                throw std::invalid_argument(a->truth + ": the ground truth's dims differ from the volume's");
        }
        std::filesystem::create_directories(a->out);

        const topology::TopologyResult topo = run_contour_tree(in.volume, context);
        ComparisonStudy study;
        study.source = in.source;
        study.volume = &in.volume;
        study.topology = &topo;
        study.request = a->cut;
        for (PluginInstance *p : plugins) {
            ComparedSimplifier c;
            c.run = simplify_tree(topo.tree, in.volume, *p, a->cut, context);
            c.labels = topology::label_voxels(topo.tree, c.run.branches, c.run.cut);
            study.runs.push_back(std::move(c));
        }
        study.overlaps = kept_overlaps(study.runs, topo.tree);
        if (truth) {
            study.truth_source = a->truth;
            study.truth = truth_scores(*truth, study.runs);
        }

        const std::filesystem::path dir(a->out);
        write_priority_lines(dir / "priority-lines.png",
                             "Priority lines: branches of " + study.runs[0].run.id + " decomposition, " +
                                 a->cut.describe(),
                             priority_rows(study.runs, plugins, a->cut));
        std::vector<LabelPanel> panels;
        for (const ComparedSimplifier &c : study.runs)
            panels.push_back({c.run.name + " (" + std::to_string(c.run.cut.kept.size()) + ")", &c.labels});
        write_label_slices(dir / "labels-axial.png", in.volume, panels);
        study.images = {"priority-lines.png", "labels-axial.png"};
        write_report_json(dir / "report.json", study);
        write_report_csv(dir / "report.csv", study);
        write_report_markdown(dir / "report.md", study);

        std::printf("%s: contour tree of %zu nodes in %.2f s\n", in.source.c_str(), topo.tree.node_count(),
                    topo.total_seconds);
        for (const ComparedSimplifier &c : study.runs)
            std::printf("  %-34s %8zu branches, %4zu kept, %.2f s\n", c.run.id.c_str(), c.run.branches.branches.size(),
                        c.run.cut.kept.size(), c.run.seconds);
        std::printf("report: %s\n", (dir / "report.md").string().c_str());
        return 0;
    });
}

} // namespace arbor::cli
