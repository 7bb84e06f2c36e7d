// `arbor tf <volume>`: per-branch transfer functions.  The volume's contour
// tree is simplified (--simplifier, --keep/--threshold), a depictor adds its
// relationship (inclusion by default; neighbour around --select), and a
// generator (residue flow by default) writes one transfer function per kept
// branch.  The generator sees the branch tree only.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "provenance.hpp"

#include "io/json_writer.hpp"
#include "input_flags.hpp"
#include "look_flags.hpp"
#include "usage_error.hpp"

#include "io/legend_png.hpp"
#include "pipeline/transfer_function_file.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct TfArgs {
    InputFlags input;
    FilterFlags filter;
    SimplifierFlags simplifier;
    CutFlags cut;
    AppearanceFlags look;
    std::string output, legend;
    uint32_t legend_size = 512;
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
    a->simplifier.add_to(*sub, context);
    a->cut.add_to(*sub, "Keep branches whose relative importance exceeds T (default: --keep 12)");
    sub->add_option("-o,--output", a->output, "Transfer functions (JSON, arbor-transfer-functions/1)")->required();
    sub->add_option("--legend", a->legend, "Write the depictor's legend (the relation wheel) as PNG");
    sub->add_option("--legend-size", a->legend_size, "Legend width and height in pixels")
        ->check(CLI::Range(64, 4096))
        ->default_val(512);
    sub->add_flag("--timings", a->timings, "Print per-stage seconds on stderr");
    a->look.add_to(*sub, context);
    context.add_command(sub, [a, &context]() {
        const SweepAxes axes{a->simplifier.names(), a->cut.keeps(), a->look.flow_rates(), a->look.shapes(),
                             a->look.hues()};
        refuse_lists(axes, "tf");
        CommandPipeline p(context, !a->input.no_cache());
        const pipeline::PluginCatalog &catalog = p->catalog();
        pipeline::Document d = pipeline::default_document();
        d.cut.keep = 12;
        a->input.apply(d.input, catalog);
        a->filter.apply(d.filters, d.auto_denoise, catalog);
        const SweepPoint point = sweep_points(axes).front();
        a->simplifier.apply(d.simplifier, point.simplifier, catalog);
        a->cut.apply(d.cut, point.keep);
        a->look.apply(d.appearance, point, catalog);
        if (!a->legend.empty()) {
            if (d.appearance.depictor.empty())
                throw UsageError("--legend needs a depictor (--relation neighbour --select BRANCH)");
            // The legend is the chosen depictor's own drawing.
            d.appearance.legend = d.appearance.depictor;
            d.appearance.legend_size = a->legend_size;
        }
        p->set_document(d);
        const auto filtered = p.run<Stage::Filter>();
        const auto tree = p.run<Stage::ContourTree>();
        const auto tf = p.run<Stage::TransferFunctions>();
        // Drawn before anything is written, so a depictor without one fails cleanly.
        std::shared_ptr<const pipeline::LegendResult> legend;
        if (!a->legend.empty())
            legend = p.run<Stage::Legend>();
        pipeline::write_transfer_functions(a->output, *tf, filtered->source, [&](io::JsonWriter &j) {
            write_provenance(j, context, p->catalog(),
                             provenance_of(p->document(), p.run<Stage::Import>().get(), filtered->filters));
        });
        if (legend)
            io::write_legend_png(a->legend, legend->size, legend->rgba);
        const pipeline::CutResult &cut = *tf->depiction->cut;
        std::printf("%s: %zu branches kept by %s, transfer functions by %s -> %s\n", filtered->source.c_str(),
                    cut.kept(), cut.decomposition->simplifier.id.c_str(), tf->generator.id.c_str(), a->output.c_str());
        if (a->timings)
            std::fprintf(stderr, "  %-20s %8.3f s\n  %-20s %8.3f s\n  %-20s %8.6f s\n", "contour tree", tree->seconds,
                         "simplification", cut.decomposition->seconds + cut.seconds, "depiction + tf",
                         tf->depiction->seconds + tf->seconds);
        return 0;
    });
}

} // namespace arbor::cli
