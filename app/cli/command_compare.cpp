// `arbor compare <volume> --simplifiers itri,persistence,volume,hypervolume
// --keep N --out DIR [--truth labels.nrrd]`: the comparison study.  The
// contour tree is computed once; every simplifier decomposes and cuts it
// with its own importance, so the runs differ in nothing else.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "comparison_report.hpp"
#include "input_flags.hpp"
#include "label_slices.hpp"
#include "look_flags.hpp"
#include "priority_lines.hpp"

#include "pipeline/branch_importance.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numeric>
#include <set>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct CompareArgs {
    InputFlags input;
    FilterFlags filter;
    SimplifierFlags simplifier;
    std::string list = "itri,persistence,volume,hypervolume";
    CutFlags cut;
    std::string out, truth;
};

constexpr std::size_t kMaxPriorityColumns = 600;

// One priority-line row per simplifier: its importance of the branches of
// the first simplifier's decomposition (so every row shows the same
// branches), and the level its own cut corresponds to.
std::vector<PriorityRow> priority_rows(const std::vector<ComparedSimplifier> &runs,
                                       const pipeline::PluginCatalog &catalog, const pipeline::CutChoice &request)
{
    const topology::BranchDecomposition &ref = runs[0].run.branches;
    std::vector<PriorityRow> rows;
    for (const ComparedSimplifier &run : runs) {
        PriorityRow row;
        row.name = run.run.name;
        row.values = pipeline::branch_importance(catalog, run.run.cut_result->decomposition->simplifier, ref);
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

// The ground truth, read as any input is (through its importer).
std::shared_ptr<const Volume> load_truth(const std::string &path, Context &context)
{
    CommandPipeline p(context, false);
    pipeline::Document d = pipeline::default_document();
    d.input.path = path;
    p->set_document(d);
    return p.run<Stage::Import>()->volume;
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
    a->cut.add_to(*sub, "Instead of --keep: keep branches whose importance exceeds T");
    sub->add_option("--out", a->out, "Folder for report.json, report.csv, report.md and the PNGs")->required();
    sub->add_option("--truth", a->truth,
                    "Ground-truth label map with the volume's dims (any importable format): Dice per label");
    a->simplifier.add_to(*sub, context, false);
    a->simplifier.used_with_several();
    context.add_command(sub, [a, &context]() {
        if (!a->cut.given())
            throw std::invalid_argument("give --keep N or --threshold T");
        const std::vector<std::string> keeps = a->cut.keeps();
        if (keeps.size() > 1)
            throw std::invalid_argument("--keep takes one value in `arbor compare`");
        CommandPipeline p(context, !a->input.no_cache());
        const pipeline::PluginCatalog &catalog = p->catalog();
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, catalog);
        d.auto_denoise = false; // analysis sees the data as it is, unless a filter is asked for
        a->filter.apply(d.filters, d.auto_denoise, catalog);
        a->cut.apply(d.cut, keeps.empty() ? std::nullopt : std::optional(keeps[0]));
        std::vector<pipeline::PluginSetting> simplifiers;
        for (const std::string &name : split_list(a->list)) {
            pipeline::PluginSetting s;
            a->simplifier.apply(s, name, catalog);
            if (std::any_of(simplifiers.begin(), simplifiers.end(), [&](const auto &x) { return x.id == s.id; }))
                throw std::invalid_argument("--simplifiers names " + s.id + " twice");
            simplifiers.push_back(std::move(s));
        }
        if (simplifiers.empty())
            throw std::invalid_argument("--simplifiers is empty");
        d.simplifier = simplifiers.front();
        p->set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        std::shared_ptr<const Volume> truth;
        if (!a->truth.empty()) {
            truth = load_truth(a->truth, context);
            if (truth->geometry().dims != filtered->volume->geometry().dims)
                throw std::invalid_argument(a->truth + ": the ground truth's dims differ from the volume's");
        }
        std::filesystem::create_directories(a->out);

        const auto tree = p.run<Stage::ContourTree>();
        ComparisonStudy study;
        study.source = filtered->source;
        study.volume = filtered->volume.get();
        study.tree = tree.get();
        study.request = d.cut;
        for (const pipeline::PluginSetting &s : simplifiers) {
            p->set_simplifier(s);
            const auto cut = p.run<Stage::Cut>();
            study.runs.emplace_back(cut, p.run<Stage::Labels>());
        }
        study.overlaps = kept_overlaps(study.runs, tree->tree);
        if (truth) {
            study.truth_source = a->truth;
            study.truth = truth_scores(*truth, study.runs);
        }

        const std::filesystem::path dir(a->out);
        write_priority_lines(dir / "priority-lines.png",
                             "Priority lines: branches of " + study.runs[0].run.id + " decomposition, " +
                                 d.cut.describe(),
                             priority_rows(study.runs, catalog, d.cut));
        std::vector<LabelPanel> panels;
        for (const ComparedSimplifier &c : study.runs)
            panels.push_back({c.run.name + " (" + std::to_string(c.run.cut.kept.size()) + ")", &c.labels});
        write_label_slices(dir / "labels-axial.png", *filtered->volume, panels);
        study.images = {"priority-lines.png", "labels-axial.png"};
        write_report_json(dir / "report.json", study);
        write_report_csv(dir / "report.csv", study);
        write_report_markdown(dir / "report.md", study);

        std::printf("%s: contour tree of %zu nodes in %.2f s\n", filtered->source.c_str(), tree->tree.node_count(),
                    tree->seconds);
        for (const ComparedSimplifier &c : study.runs)
            std::printf("  %-34s %8zu branches, %4zu kept, %.2f s\n", c.run.id.c_str(), c.run.branches.branches.size(),
                        c.run.cut.kept.size(), c.run.seconds);
        std::printf("report: %s\n", (dir / "report.md").string().c_str());
        return 0;
    });
}

} // namespace arbor::cli
