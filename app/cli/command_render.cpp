// `arbor render <volume> --tf tf.json -o image.png`: renders with transfer
// functions written by `arbor tf` (or edited since).  The labels are rebuilt
// from the volume with the simplifier and cut the file records, and the
// pipeline checks them against the file's branches, so functions made for
// another volume or another simplification are refused instead of misapplied.
#include "command_pipeline.hpp"
#include "commands.hpp"
#include "input_flags.hpp"
#include "view_flags.hpp"

#include "io/image_output.hpp"
#include "pipeline/transfer_function_file.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

using pipeline::Stage;

struct RenderArgs {
    InputFlags input;
    FilterFlags filter;
    ViewFlags view;
    std::string tf, output;
};

} // namespace

void add_render_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand("render", "Render a volume with per-branch transfer functions from `arbor tf`");
    auto a = std::make_shared<RenderArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--tf", a->tf, "Transfer functions (arbor-transfer-functions/1 JSON)")->required();
    sub->add_option("-o,--output", a->output, "Image to write (.png or .exr)")->required();
    a->view.add_to(*sub, context);
    context.add_command(sub, [a, &context]() {
        const pipeline::StoredTransferFunctions stored = pipeline::read_transfer_functions(a->tf);
        CommandPipeline p(context, !a->input.no_cache());
        const pipeline::PluginCatalog &catalog = p->catalog();
        pipeline::Document d = pipeline::default_document();
        a->input.apply(d.input, catalog);
        a->filter.apply(d.filters, d.auto_denoise, catalog);
        d.simplifier = {stored.simplifier_id, "", {}};
        d.cut = pipeline::CutChoice::parse(stored.cut);
        d.appearance.transfer_functions_file = a->tf;
        a->view.apply(d.view, catalog);
        p->set_document(d);
        const auto render = p.run<Stage::Render>();
        io::write_image(a->output, render->image);
        std::printf("%s: %u branches rendered by %s -> %s (%.0f%% covered)\n", p.run<Stage::Filter>()->source.c_str(),
                    p.run<Stage::TransferFunctions>()->functions->branch_count(), render->renderer.id.c_str(),
                    a->output.c_str(), 100.0 * io::covered_fraction(render->image));
        return 0;
    });
}

} // namespace arbor::cli
