// `arbor run <volume | --phantom head> -o out.png`: the main job.  Import,
// (filter), contour tree, ITri simplification (branch count from the knee of
// the importance curve unless --keep/--threshold), residue-flow transfer
// functions with the inclusion depiction, label-aware rendering; then the
// image, the relation-wheel legend and a report that makes it reproducible.
#include "commands.hpp"
#include "render_options.hpp"
#include "run_report.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "transfer_function_stage.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "core/stopwatch.hpp"
#include "io/image_output.hpp"
#include "io/png_output.hpp"
#include "topology/importance_knee.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct RunArgs {
    VolumeInput input;
    FilterInput filter;
    PluginChoice simplifiers{ARBOR_KIND_SIMPLIFIER, "simplifier"};
    TransferFunctionStage stage;
    RenderOptions render;
    std::string simplifier = "itri";
    CutRequest cut;
    std::string output, legend, report;
};

std::filesystem::path beside(const std::filesystem::path &image, const std::string &suffix)
{
    return image.parent_path() / (image.stem().string() + suffix);
}

} // namespace

void add_run_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "run", "The main job: topology-driven transfer functions and a rendered image of a volume");
    auto a = std::make_shared<RunArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("-o,--output", a->output, "Image to write (.png or .exr)")->required();
    sub->add_option("--simplifier", a->simplifier, "Simplifier plugin (id or last part)")->default_val("itri");
    add_cut_options(*sub, a->cut,
                    "Keep branches whose relative importance exceeds T (default: the knee of the importance curve)");
    sub->add_option("--legend", a->legend, "Relation-wheel legend PNG (default: <output>-legend.png)");
    sub->add_option("--report", a->report, "Report JSON, with a Markdown twin (default: <output>.report.json)");
    a->stage.add_to(*sub, context);
    a->render.add_to(*sub, context);
    a->simplifiers.add_to(*sub, context, "Simplifier options");
    context.add_command(sub, [a, &context]() {
        a->stage.validate(false);
        const std::filesystem::path output(a->output);
        const std::filesystem::path legend_path = a->legend.empty() ? beside(output, "-legend.png") : std::filesystem::path(a->legend);
        const std::filesystem::path report_path =
            a->report.empty() ? beside(output, ".report.json") : std::filesystem::path(a->report);
        for (const std::filesystem::path &p : {output, legend_path, report_path})
            if (!p.parent_path().empty())
                std::filesystem::create_directories(p.parent_path());
        PluginInstance &simplifier = a->simplifiers.resolve(a->simplifier);

        RunReport report;
        Stopwatch clock;
        LoadedVolume in = a->input.load();
        report.stage("import", clock.lap());
        const PluginInstance *filter = a->filter.apply(in, context);
        if (filter)
            report.stage("filter", clock.lap());
        const topology::TopologyResult topo = run_contour_tree(in.volume, context);
        report.stage("contour tree", clock.lap());
        CutRequest cut = a->cut;
        SimplifiedTree s;
        if (!cut.keep && !cut.threshold) {
            // Decompose once, find the knee, then cut there.
            cut.keep = 1;
            s = simplify_tree(topo.tree, in.volume, simplifier, cut, context);
            const topology::KneeChoice knee = topology::knee_branch_count(s.branches);
            cut.keep = knee.keep;
            s.cut = topology::cut_by_count(s.branches, knee.keep);
            report.knee = knee;
        } else {
            s = simplify_tree(topo.tree, in.volume, simplifier, cut, context);
        }
        report.stage("simplification", clock.lap());
        const BranchTreeRecord tree(topo.tree, s.branches, s.cut, in.volume);
        const double range[2] = {s.branches.global_min, s.branches.global_max};
        const TransferFunctionResult tf = a->stage.run(tree, in.volume, range, context);
        report.stage("transfer functions", clock.lap());
        const std::vector<uint32_t> labels = topology::label_voxels(topo.tree, s.branches, s.cut);
        report.stage("labels", clock.lap());
        const RenderedImage image = a->render.render(in.volume, labels, *tf.functions, context);
        report.stage("render", clock.lap());

        // The legend: the relation wheel around the selected branch, or the
        // deepest one (the innermost structure).
        uint32_t selected = 0;
        for (uint32_t b = 0; b < tree.size(); ++b)
            if (tree.record().depth[b] > tree.record().depth[selected])
                selected = b;
        if (a->stage.selected())
            selected = static_cast<uint32_t>(*a->stage.selected());
        arbor_depiction_request wheel = tf.request;
        wheel.selected_branch = static_cast<int32_t>(selected);
        PluginInstance &neighbour = a->stage.depictors().resolve("neighbour");
        const cv::Mat legend = a->stage.legend(neighbour, wheel, 512);

        io::write_image(output, image);
        io::write_png(legend_path, legend);
        report.stage("write", clock.lap());
        report.source = in.source;
        report.importer = in.importer_id.empty() ? "" : in.importer_id + " " + in.importer_version;
        report.filter = filter;
        report.volume = &in.volume;
        report.topology = &topo;
        report.simplified = &s;
        report.cut = cut;
        report.tree = &tree.record();
        report.tf = &tf;
        report.renderer = &a->render.renderer();
        report.orbit = a->render.orbit();
        report.width = image.width;
        report.height = image.height;
        report.coverage = io::covered_fraction(image);
        report.image = output.string();
        report.legend = legend_path.string();
        report.legend_selected = selected;
        write_run_report(report_path, report);

        std::printf("%s: %zu branches, %zu kept (%s), %ux%u image, %.0f%% of it covered\n", in.source.c_str(),
                    s.branches.branches.size(), s.cut.kept.size(),
                    report.knee ? "knee of the ITri curve" : cut.describe().c_str(), image.width, image.height,
                    100.0 * report.coverage);
        std::printf("image:  %s\nlegend: %s\nreport: %s and %s\n", output.string().c_str(),
                    legend_path.string().c_str(), report_path.string().c_str(),
                    report_path.parent_path().append(report_path.stem().string() + ".md").string().c_str());
        return 0;
    });
}

} // namespace arbor::cli
