// `arbor tree <volume> --json out.json`: the contour tree (nodes, arcs) and
// its persistence branch decomposition with every branch's measures, in the
// columnar arbor-contour-tree/2 format (io/contour_tree_json.hpp); with
// --keep/--threshold also the simplified hierarchy and its voxel labels.
#include "commands.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "io/contour_tree_json.hpp"
#include "io/label_map_output.hpp"
#include "topology/simplification.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace arbor::cli {

namespace {

struct TreeArgs {
    VolumeInput input;
    FilterInput filter;
    std::string json;
    std::string labels;
    CutRequest cut; // optional here: without one, the whole hierarchy
    bool timings = false;
};

} // namespace

void add_tree_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "tree", "Compute the contour tree and its branch decomposition (persistence) with measures");
    auto a = std::make_shared<TreeArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--json", a->json, "Write nodes, arcs and branches with measures as JSON")->required();
    add_cut_options(*sub, a->cut, "Also cut the hierarchy at this relative persistence, in [0, 1]");
    sub->add_option("--labels", a->labels, "With --keep/--threshold: write the voxel -> branch labels (NRRD)");
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    context.add_command(sub, [a, &context]() {
        if (!a->labels.empty() && !a->cut.keep && !a->cut.threshold)
            throw std::invalid_argument("--labels needs --keep or --threshold");
        LoadedVolume in = a->input.load();
        a->filter.apply(in, context);
        const topology::TopologyResult topo = run_topology(in.volume, topology::persistence_importance(), context);
        std::optional<topology::SimplificationCut> cut;
        if (a->cut.keep)
            cut = topology::cut_by_count(topo.branches, *a->cut.keep);
        else if (a->cut.threshold)
            cut = topology::cut_by_threshold(topo.branches, *a->cut.threshold);
        io::write_contour_tree_json(a->json, {in.source, &in.volume, &topo, cut ? &*cut : nullptr});
        if (cut && !a->labels.empty())
            io::write_label_map(a->labels, in.volume.geometry(), "arbor branch labels of " + in.source,
                                topology::label_voxels(topo.tree, topo.branches, *cut),
                                kept_label_names(topo.branches, *cut));
        std::printf("%s: %zu nodes, %zu arcs, %zu branches%s -> %s\n", in.source.c_str(),
                    topo.tree.node_count(), topo.tree.arc_count(), topo.branches.branches.size(),
                    cut ? (", " + std::to_string(cut->kept.size()) + " kept").c_str() : "", a->json.c_str());
        if (a->timings)
            print_timings(topo, in.volume);
        return 0;
    });
}

} // namespace arbor::cli
