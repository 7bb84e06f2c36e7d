// `arbor tf <volume>`: per-branch transfer functions.  The volume's contour
// tree is simplified (--simplifier, --keep/--threshold), a depictor adds its
// relationship (inclusion by default; neighbour around --select), and a
// generator (residue flow by default) writes one transfer function per kept
// branch.  The generator sees the branch tree only.
#include "commands.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "transfer_function_json.hpp"
#include "transfer_function_stage.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "io/png_output.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct TfArgs {
    VolumeInput input;
    FilterInput filter;
    PluginChoice simplifiers{ARBOR_KIND_SIMPLIFIER, "simplifier"};
    TransferFunctionStage stage;
    std::string simplifier = "itri";
    CutRequest cut;
    std::string output, legend;
    int legend_size = 512;
    bool timings = false;
};

} // namespace

void add_tf_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "tf", "Generate one transfer function per branch (residue-flow opacity, harmonic colours)");
    auto a = std::make_shared<TfArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--simplifier", a->simplifier, "Simplifier plugin (id or last part)")->default_val("itri");
    add_cut_options(*sub, a->cut, "Keep branches whose relative importance exceeds T (default: --keep 12)");
    sub->add_option("-o,--output", a->output, "Transfer functions (JSON, arbor-transfer-functions/1)")->required();
    sub->add_option("--legend", a->legend, "Write the depictor's legend (the relation wheel) as PNG");
    sub->add_option("--legend-size", a->legend_size, "Legend width and height in pixels")
        ->check(CLI::Range(64, 4096))
        ->default_val(512);
    sub->add_flag("--timings", a->timings, "Print per-stage seconds on stderr");
    a->stage.add_to(*sub, context);
    a->simplifiers.add_to(*sub, context, "Simplifier options");
    context.add_command(sub, [a, &context]() {
        if (!a->cut.keep && !a->cut.threshold)
            a->cut.keep = 12;
        a->stage.validate(!a->legend.empty());
        PluginInstance &simplifier = a->simplifiers.resolve(a->simplifier);
        LoadedVolume in = a->input.load();
        a->filter.apply(in, context);
        const topology::TopologyResult topo = run_contour_tree(in.volume, context);
        const SimplifiedTree s = simplify_tree(topo.tree, in.volume, simplifier, a->cut, context);
        const BranchTreeRecord tree(topo.tree, s.branches, s.cut, in.volume);
        const double range[2] = {s.branches.global_min, s.branches.global_max};
        const TransferFunctionResult r = a->stage.run(tree, in.volume, range, context);
        // Drawn before anything is written, so a depictor without one fails cleanly.
        const cv::Mat legend = a->legend.empty() ? cv::Mat() : a->stage.legend(*r.depictor, r.request, a->legend_size);

        TransferFunctionFile f;
        f.source = in.source;
        f.simplifier_id = s.id;
        f.cut = a->cut.describe();
        f.generator = r.generator;
        f.depictor = r.depictor;
        f.selected_branch = r.request.selected_branch;
        f.value_range[0] = range[0];
        f.value_range[1] = range[1];
        f.tree = &tree.record();
        f.depiction = r.depictor ? &r.depiction->record() : nullptr;
        f.functions = r.functions.get();
        write_transfer_functions(a->output, f);
        if (!a->legend.empty())
            io::write_png(a->legend, legend);
        std::printf("%s: %u branches kept by %s, transfer functions by %s -> %s\n", in.source.c_str(), tree.size(),
                    s.id.c_str(), r.generator->id().c_str(), a->output.c_str());
        if (a->timings)
            std::fprintf(stderr, "  %-20s %8.3f s\n  %-20s %8.3f s\n  %-20s %8.6f s\n", "contour tree",
                         topo.total_seconds, "simplification", s.seconds, "depiction + tf", r.seconds);
        return 0;
    });
}

} // namespace arbor::cli
