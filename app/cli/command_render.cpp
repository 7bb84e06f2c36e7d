// `arbor render <volume> --tf tf.json -o image.png`: renders with transfer
// functions written by `arbor tf` (or edited since).  The labels are rebuilt
// from the volume with the simplifier and cut the file records, and checked
// against the file's branches, so functions made for another volume or
// another simplification are refused instead of misapplied.
#include "commands.hpp"
#include "render_options.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "transfer_function_json.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "io/image_output.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct RenderArgs {
    VolumeInput input;
    FilterInput filter;
    PluginChoice simplifiers{ARBOR_KIND_SIMPLIFIER, "simplifier"};
    RenderOptions render;
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
    a->render.add_to(*sub, context);
    a->simplifiers.add_to(*sub, context, "Simplifier options");
    context.add_command(sub, [a, &context]() {
        const StoredTransferFunctions stored = read_transfer_functions(a->tf);
        const CutRequest cut = CutRequest::parse(stored.cut);
        PluginInstance &simplifier = a->simplifiers.resolve(stored.simplifier_id);
        LoadedVolume in = a->input.load();
        a->filter.apply(in, context);
        const topology::TopologyResult topo = run_contour_tree(in.volume, context);
        const SimplifiedTree s = simplify_tree(topo.tree, in.volume, simplifier, cut, context);
        const std::size_t n = stored.extremum_vertex.size();
        bool same = s.cut.kept.size() == n;
        for (std::size_t k = 0; same && k < n; ++k)
            same = topo.tree.node_vertex[s.branches.branches[s.cut.kept[k]].extremum_node] ==
                   static_cast<uint32_t>(stored.extremum_vertex[k]);
        if (!same)
            throw std::invalid_argument(a->tf + ": its " + std::to_string(n) + " branches (made from " + stored.source +
                                        ") are not the branches " + stored.simplifier_id + " keeps in " + in.source +
                                        " with " + stored.cut + "; regenerate them with `arbor tf`");
        const std::vector<uint32_t> labels = topology::label_voxels(topo.tree, s.branches, s.cut);
        const RenderedImage image = a->render.render(in.volume, labels, *stored.functions, context);
        io::write_image(a->output, image);
        std::printf("%s: %zu branches rendered by %s -> %s (%.0f%% covered)\n", in.source.c_str(), n,
                    a->render.renderer().id().c_str(), a->output.c_str(), 100.0 * io::covered_fraction(image));
        return 0;
    });
}

} // namespace arbor::cli
