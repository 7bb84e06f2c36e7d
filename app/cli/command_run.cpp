// `arbor run <volume | --phantom head | --session s.json> -o out.png`: the
// main job.  Import, (filters), contour tree, ITri simplification (branch
// count from the knee of the importance curve unless --keep/--threshold),
// residue-flow transfer functions with the inclusion depiction, label-aware
// rendering; then the image, the relation-wheel legend and a report that
// makes it reproducible, and on request the session (--save-session) and the
// label map that was rendered (--labels).
//
// Sweeps: --simplifier, --keep, --flow-rate, --shape and --hues take comma
// lists; every combination is rendered from the one contour tree into its
// own image (out-q30-ramp.png ...), beside a captioned contact sheet (out.png)
// and one report with every run and how often each stage ran.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"
#include "look_flags.hpp"
#include "provenance.hpp"
#include "run_report.hpp"
#include "usage_error.hpp"
#include "view_flags.hpp"

#include "core/ct_tissue.hpp"
#include "core/stopwatch.hpp"
#include "io/contact_sheet.hpp"
#include "io/image_output.hpp"
#include "io/label_map_output.hpp"
#include "io/legend_png.hpp"
#include "pipeline/session.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

namespace fs = std::filesystem;
using pipeline::Stage;

struct RunArgs {
    InputFlags input;
    FilterFlags filter;
    SimplifierFlags simplifier;
    CutFlags cut;
    AppearanceFlags look;
    ViewFlags view;
    std::string output, legend, report, session, save_session, labels;
};

// out.png + "-legend.png" -> out-legend.png
fs::path beside(const fs::path &file, const std::string &suffix, const std::string &extension = "")
{
    return file.parent_path() / (file.stem().string() + suffix + (extension.empty() ? file.extension().string() : extension));
}

pipeline::Document base_document(const RunArgs &a, const pipeline::PluginCatalog &catalog)
{
    if (a.session.empty())
        return pipeline::default_document();
    pipeline::SessionRead read = pipeline::read_session(a.session, catalog, !a.input.given());
    for (const std::string &w : read.warnings)
        log_message(ARBOR_LOG_WARNING, "", w);
    return read.document;
}

// Per branch: what it is, the values (HU on CT) it spans, and its share of
// the picture.  One line a branch for one run; a line a run for a sweep.
void print_branches(const RenderedRun &run, const ValueMapping &mapping, bool one_line)
{
    const arbor_branch_tree &t = run.cut->tree->record();
    const TransferFunctions &tf = *run.tf->functions;
    const bool hu = mapping.unit == "HU";
    if (run.render->image.label_visibility.empty()) {
        std::printf("  (the renderer %s does not measure visibility)\n", run.render->renderer.id.c_str());
        return;
    }
    if (one_line) {
        std::printf("  visibility:");
        for (uint32_t b = 0; b < t.branch_count; ++b)
            std::printf(" %u:%.0f%%", b, 100.0 * visibility_share(run.render->image, b));
        std::printf("\n");
        return;
    }
    std::printf("  %5s %-7s %5s %-22s %-36s %10s  %-13s %s\n", "label", "kind", "depth", hu ? "HU range" : "value range",
                hu ? "tissues" : "", "visibility", "shape", "colour");
    for (uint32_t b = 0; b < t.branch_count; ++b) {
        const double lo = mapping.physical(tf.domain(b).first), hi = mapping.physical(tf.domain(b).second);
        std::string tissues;
        if (hu)
            for (const std::string &name : ct_tissues_spanned(std::min(lo, hi), std::max(lo, hi)))
                tissues += (tissues.empty() ? "" : ", ") + name;
        char range[64];
        std::snprintf(range, sizeof range, "%.6g .. %.6g", std::min(lo, hi), std::max(lo, hi));
        // The generator's note: "shape: why; colour: family (why)".
        const std::string note = tf.note(b);
        const std::size_t colour_at = note.find("colour: ");
        const std::string colour =
            colour_at == std::string::npos ? "" : note.substr(colour_at + 8, note.find(" (", colour_at) - colour_at - 8);
        std::printf("  %5u %-7s %5u %-22s %-36s %9.1f%%  %-13s %s\n", b,
                    b == 0 ? "root" : (t.extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM ? "minimum" : "maximum"), t.depth[b],
                    range, tissues.c_str(), 100.0 * visibility_share(run.render->image, b),
                    colour_at == 0 ? "" : note.substr(0, note.find(':')).c_str(), colour.c_str());
    }
}

// The session of a run: the document, with the importer as it was used (the
// one probing chose, every parameter as read back after the import).
pipeline::Document session_of(pipeline::Document d, const pipeline::ImportResult &import)
{
    if (!d.input.phantom)
        d.input.importer = import.importer;
    return d;
}

// The import without its voxels: what the report and the session say of it.
std::shared_ptr<const pipeline::ImportResult> description_of(const pipeline::ImportResult &import)
{
    auto d = std::make_shared<pipeline::ImportResult>(import);
    d->volume.reset();
    return d;
}

} // namespace

void add_run_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "run", "The main job: topology-driven transfer functions and a rendered image of a volume");
    sub->footer("Sessions: --save-session s.json writes every choice of the run (input, filters, plugins with all "
                "their parameters, cut, selection, camera, image size, renderer); --session s.json reproduces it, "
                "and any flag given beside it overrides the session's value.\n"
                "Sweeps: --simplifier, --keep, --flow-rate, --shape and --hues take comma lists; every combination "
                "is rendered from one contour tree (out-q30-ramp.png ...), with a contact sheet (out.png) and one "
                "report.\n"
                "The contour tree is cached on disk (keyed by the voxels it was built on): reopening a volume does "
                "not rebuild it; --no-cache bypasses the cache.");
    auto a = std::make_shared<RunArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("-o,--output", a->output,
                    "Image to write (.png or .exr); for a sweep, the contact sheet (each run's image beside it)")
        ->required();
    sub->add_option("--session", a->session, "Start from this session (arbor-session/1); flags given override it")
        ->group("Session");
    sub->add_option("--save-session", a->save_session, "Write the session of this run (for a sweep: one per run)")
        ->group("Session");
    a->simplifier.add_to(*sub, context);
    a->cut.add_to(*sub, "Keep branches whose relative importance exceeds T (default: the knee of the importance curve)");
    sub->add_option("--labels", a->labels,
                    "Write the label map that was rendered (NRRD, with a 3D Slicer colour table .ctbl beside it)");
    sub->add_option("--legend", a->legend, "Relation-wheel legend PNG (default: <output>-legend.png)");
    sub->add_option("--report", a->report, "Report JSON, with a Markdown twin (default: <output>.report.json)");
    a->look.add_to(*sub, context);
    a->view.add_to(*sub, context);
    context.add_command(sub, [a, &context]() {
        const fs::path output(a->output);
        const std::string ext = output.extension().string();
        if (ext != ".png" && ext != ".exr")
            throw UsageError(output.string() + ": images are written as .png or .exr");
        // One pass: the input is filtered once and every point of a sweep
        // is cut from the one tree, so the input's voxels need not stay
        // beside the filtered ones through the tree and the render, nor the
        // tree's segmentation beside the label map after the last cut.
        CommandPipeline p(context, !a->input.no_cache(), /*single_pass=*/true);
        const pipeline::PluginCatalog &catalog = p->catalog();

        pipeline::Document base = base_document(*a, catalog);
        a->input.apply(base.input, catalog);
        a->filter.apply(base.filters, base.auto_denoise, catalog);
        const SweepAxes axes{a->simplifier.names(), a->cut.keeps(), a->look.flow_rates(), a->look.shapes(),
                             a->look.hues()};
        const std::vector<SweepPoint> points = sweep_points(axes);
        const bool sweep = points.size() > 1;
        if (sweep && !a->legend.empty())
            throw UsageError("--legend names one file; a sweep writes one legend beside each image");

        const fs::path report_path = a->report.empty() ? beside(output, ".report", ".json") : fs::path(a->report);
        for (const fs::path &f : {output, report_path})
            if (!f.parent_path().empty())
                fs::create_directories(f.parent_path());

        RunReport report;
        std::vector<std::shared_ptr<const pipeline::LabelsResult>> labels;
        for (const SweepPoint &point : points) {
            pipeline::Document d = base;
            a->simplifier.apply(d.simplifier, point.simplifier, catalog);
            a->cut.apply(d.cut, point.keep);
            a->look.apply(d.appearance, point, catalog);
            a->view.apply(d.view, catalog);
            p->set_document(d);
            if (&point == &points.back())
                p->declare_last_document();
            if (!report.import)
                report.import = description_of(*p.run<Stage::Import>());

            RenderedRun run;
            run.name = point.name;
            run.caption = point.caption;
            run.render = p.run<Stage::Render>();
            run.tf = p.run<Stage::TransferFunctions>();
            run.cut = p.run<Stage::Cut>();
            labels.push_back(p.run<Stage::Labels>());
            run.document = p->document();
            if (!run.document.appearance.legend.empty())
                run.legend = p.run<Stage::Legend>();

            Stopwatch watch;
            run.image = sweep ? beside(output, "-" + point.name) : output;
            io::write_image(run.image, run.render->image);
            if (run.legend) {
                run.legend_image = a->legend.empty() ? beside(run.image, "-legend", ".png") : fs::path(a->legend);
                io::write_legend_png(run.legend_image, run.legend->size, run.legend->rgba);
            }
            run.coverage = io::covered_fraction(run.render->image);
            if (!a->save_session.empty()) {
                const fs::path s = sweep ? beside(a->save_session, "-" + point.name) : fs::path(a->save_session);
                pipeline::write_session(s, session_of(run.document, *report.import), catalog);
                report.session = sweep ? fs::path() : s;
            }
            run.write_seconds = watch.lap();
            report.runs.push_back(std::move(run));
        }
        report.filtered = p.run<Stage::Filter>();
        // The tree as the pass left it: after the last cut, without its
        // segmentation, and no longer current (a request would compute it
        // again).
        report.tree = p->latest<Stage::ContourTree>();

        if (!a->labels.empty()) {
            // One map when every run rendered the same labels, else one per run.
            const bool same = std::all_of(labels.begin(), labels.end(), [&](const auto &l) { return l == labels[0]; });
            for (std::size_t i = 0; i < (same ? 1 : labels.size()); ++i) {
                const fs::path path = same ? fs::path(a->labels) : beside(a->labels, "-" + points[i].name);
                io::write_label_map(path, report.filtered->volume->geometry(),
                                    "arbor labels of " + report.filtered->source, labels[i]->labels, labels[i]->names);
            }
            report.labels = same ? fs::path(a->labels) : fs::path();
        }
        if (sweep) {
            report.contact_sheet = beside(output, "", ".png");
            std::vector<io::ContactSheetTile> tiles;
            for (const RenderedRun &run : report.runs)
                tiles.push_back({&run.render->image, run.caption});
            io::write_contact_sheet(report.contact_sheet, report.filtered->source, tiles);
        }
        report.stage_runs = p->stage_runs();
        report.provenance = provenance_text(
            context, catalog, provenance_of(report.runs.front().document, report.import.get(), report.filtered->filters));
        write_run_report(report_path, report);

        for (const RenderedRun &run : report.runs) {
            const pipeline::CutResult &cut = *run.cut;
            std::printf("%s%s: %zu branches, %zu kept (%s), %ux%u image, %.0f%% of it covered\n",
                        report.filtered->source.c_str(), run.caption.empty() ? "" : (" [" + run.caption + "]").c_str(),
                        cut.decomposition->branches.branches.size(), cut.kept(),
                        cut.knee ? "knee of the ITri curve" : cut.requested.describe().c_str(),
                        run.render->image.width, run.render->image.height, 100.0 * run.coverage);
            print_branches(run, report.filtered->volume->mapping(), sweep);
        }
        if (sweep)
            std::printf("images: %zu beside %s (the contact sheet)\n", report.runs.size(),
                        report.contact_sheet.string().c_str());
        else
            std::printf("image:  %s\nlegend: %s\n", output.string().c_str(),
                        report.runs[0].legend_image.string().c_str());
        std::printf("report: %s and %s\n", report_path.string().c_str(),
                    beside(report_path, "", ".md").string().c_str());
        if (!report.session.empty())
            std::printf("session: %s\n", report.session.string().c_str());
        return 0;
    });
}

} // namespace arbor::cli
