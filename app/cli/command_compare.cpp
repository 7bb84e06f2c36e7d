// `arbor compare <volume> --simplifiers itri,n-measure:measures=persistence+volume
// --keep 4,8,16,32 [--filter none --filter gaussian:sigma=1] --out DIR
// [--truth labels.nrrd]`: a comparison study in one command.  The contour
// tree is computed once per filter setting; every simplifier setting
// decomposes it once with its own importance and every cut is made on that,
// so the runs differ in nothing else.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "comparison_report.hpp"
#include "input_flags.hpp"
#include "look_flags.hpp"
#include "provenance.hpp"
#include "study_figures.hpp"
#include "study_grid.hpp"
#include "study_run.hpp"
#include "usage_error.hpp"

#include "io/json_writer.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct CompareArgs {
    InputFlags input;
    FilterFlags filter;
    SimplifierFlags simplifier;
    std::string list = "itri,persistence,volume,hypervolume";
    CutFlags cut;
    std::string out, truth, truth_colors, scoring = "exclusive", axis = "axial";
    std::optional<int64_t> slice;
    double dpi = 150;
};

std::vector<StudySimplifier> simplifier_settings(const CompareArgs &a, const pipeline::PluginCatalog &catalog)
{
    std::vector<StudySimplifier> out;
    for (const std::string &entry : simplifier_entries(a.list)) {
        pipeline::PluginSetting spec = pipeline::parse_plugin_spec(entry, "--simplifiers");
        pipeline::PluginSetting s;
        a.simplifier.apply(s, spec.id, catalog);
        for (const auto &[key, value] : spec.params)
            s.params[key] = value; // the entry's own values beat --NAME.key flags
        s = catalog.resolve(ARBOR_KIND_SIMPLIFIER, s);
        for (const StudySimplifier &other : out)
            if (other.setting == s)
                throw UsageError("--simplifiers: " + entry + " is the same setting as " + other.label);
        out.push_back({s, entry});
    }
    if (out.empty())
        throw UsageError("--simplifiers is empty");
    return out;
}

} // namespace

void add_compare_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "compare", "A comparison study: simplifiers x cuts x filters on one contour tree per filter; kept "
                   "branches, overlaps, Dice/precision/recall against a ground truth, priority lines, figures");
    auto a = std::make_shared<CompareArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context,
                     "A filter setting of the study: NAME[:key=value,...], filters of one chain joined by '+' "
                     "(median:size=3+gaussian:sigma=1), none for the data as it is; give it several times to "
                     "compare settings (the tree is computed once per setting); default none");
    sub->add_option("--simplifiers", a->list,
                    "Simplifier settings: ids or their last parts, each with its own parameters "
                    "(itri,n-measure:measures=persistence+volume,com.example.pv:exponent=2); one plugin may appear "
                    "with several settings; the first one's branches are the columns of the priority lines")
        ->default_val("itri,persistence,volume,hypervolume");
    a->cut.add_to(*sub, "Instead of --keep: keep branches whose importance exceeds T; a comma list sweeps");
    sub->add_option("--out", a->out,
                    "Folder for report.json, timings.json, study.csv, report.csv, report.md and the figures")
        ->required();
    sub->add_option("--truth", a->truth,
                    "Ground-truth label map with the volume's dims (any importable format): Dice, precision and "
                    "recall per structure; names and colours from a .ctbl beside it");
    sub->add_option("--truth-colors", a->truth_colors,
                    "3D Slicer colour table (.ctbl) naming the truth's labels (default: the one beside --truth)");
    sub->add_option("--score", a->scoring,
                    "Region of a kept branch: exclusive (the voxels labelled with it) or subtree (with every kept "
                    "branch below it)")
        ->check(CLI::IsMember({"exclusive", "subtree"}))
        ->default_val("exclusive");
    sub->add_option("--slice-axis", a->axis, "Slice of the label panels: axial, coronal or sagittal")
        ->check(CLI::IsMember({"axial", "coronal", "sagittal"}))
        ->default_val("axial");
    sub->add_option("--slice", a->slice,
                    "Index of the panels' slice (default: the one with the most ground-truth voxels, else the "
                    "middle)");
    sub->add_option("--dpi", a->dpi, "Resolution of the PNG figures (each has an SVG twin)")
        ->check(CLI::Range(18.0, 2400.0))
        ->default_val(150);
    a->simplifier.add_to(*sub, context, false);
    a->simplifier.used_with_several();
    context.add_command(sub, [a, &context]() {
        if (!a->cut.given())
            throw UsageError("give --keep N[,N...] or --threshold T[,T...]");
        CommandPipeline p(context, !a->input.no_cache());
        const pipeline::PluginCatalog &catalog = p->catalog();
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, catalog);
        d.auto_denoise = false; // analysis sees the data as it is, unless filters are asked for

        StudyRequest request;
        for (auto &[label, chain] : a->filter.sweep_chains(catalog))
            request.grid.filters.push_back({std::move(chain), label});
        request.grid.simplifiers = simplifier_settings(*a, catalog);
        request.grid.cuts = a->cut.cuts();
        request.scoring = a->scoring == "subtree" ? RegionScoring::Subtree : RegionScoring::Exclusive;
        request.truth_path = a->truth;
        request.truth_colors_path = a->truth_colors;
        if (!a->truth_colors.empty() && a->truth.empty())
            throw UsageError("--truth-colors names the labels of a --truth; give one");
        p->set_document(d);
        std::filesystem::create_directories(a->out);

        const StudyOutcome study = run_study(*p, context, request);

        const std::filesystem::path dir(a->out);
        FigureOptions figures;
        figures.dpi = a->dpi;
        figures.axis = a->axis == "coronal" ? SliceAxis::Coronal
                                            : (a->axis == "sagittal" ? SliceAxis::Sagittal : SliceAxis::Axial);
        figures.slice = a->slice;
        StudyReport report;
        report.study = &study;
        report.figures = write_study_figures(dir, study, figures);
        const auto import = p.run<Stage::Import>();
        report.provenance = [&](io::JsonWriter &j) {
            ProvenanceParts parts;
            parts.import = import.get();
            parts.input = d.input;
            for (const StudySimplifier &s : study.grid.simplifiers)
                parts.plugins.emplace_back("simplifier", s.setting);
            for (const FilterOutcome &f : study.filters)
                for (const pipeline::PluginSetting &s : f.filter.chain)
                    parts.plugins.emplace_back("filter (" + f.filter.label + ")", s);
            write_provenance(j, context, catalog, parts);
        };
        write_report_json(dir / "report.json", report);
        write_timings_json(dir / "timings.json", study);
        write_study_csv(dir / "study.csv", study);
        write_kept_csv(dir / "report.csv", study);
        write_report_markdown(dir / "report.md", report);
        std::printf("report: %s (study.csv, report.json, %zu figures)\n", (dir / "report.md").string().c_str(),
                    report.figures.size() / 2);
        return 0;
    });
}

} // namespace arbor::cli
