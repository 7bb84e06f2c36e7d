// `arbor simplify <volume> --simplifier ID (--threshold T | --keep N)
// --json out.json [--labels labels.nrrd]`: the contour tree simplified by
// one simplifier plugin, its kept branches with measures and importance,
// and the voxel -> branch label map.
#include "commands.hpp"
#include "simplification_run.hpp"
#include "plugin_choice.hpp"
#include "topology_run.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "io/label_map_output.hpp"
#include "io/topology_json.hpp"

#include <cstdio>
#include <memory>

namespace arbor::cli {

namespace {

struct SimplifyArgs {
    VolumeInput input;
    FilterInput filter;
    PluginChoice simplifiers{ARBOR_KIND_SIMPLIFIER, "simplifier"};
    std::string simplifier = "itri";
    CutRequest cut;
    std::string json, labels;
    bool timings = false;
};

void write_json(const std::string &path, const LoadedVolume &in, const topology::TopologyResult &topo,
                const SimplifiedTree &s, const CutRequest &request)
{
    io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
        j.field("format", "arbor-simplified-tree/1");
        io::write_volume_summary(j, in.source, in.volume.geometry());
        {
            const io::JsonWriter::Scope simplifier = j.object("simplifier");
            write_simplifier_fields(j, s);
        }
        write_cut(j, request);
        io::write_contour_tree_summary(j, topo.tree, topo.total_seconds, s.branches.branches.size());
        write_kept_branches(j, "kept_branches", topo.tree, in.volume, s);
        const io::JsonWriter::Scope seconds = j.object("seconds");
        j.field("contour_tree", topo.total_seconds);
        j.field("simplification", s.seconds);
    });
}

} // namespace

void add_simplify_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "simplify", "Simplify the contour tree with a simplifier plugin; write the kept branches and labels");
    auto a = std::make_shared<SimplifyArgs>();
    a->input.add_to(*sub, context);
    a->filter.add_to(*sub, context);
    sub->add_option("--simplifier", a->simplifier,
                    "Simplifier plugin: an id or its last part (itri, persistence, volume, hypervolume, "
                    "n-measure)")
        ->default_val("itri");
    add_cut_options(*sub, a->cut,
                    "Keep branches whose relative importance exceeds T (ITri and n-measure importances are "
                    "products of relative measures: small numbers)");
    sub->add_option("--json", a->json, "Write the kept branches with measures and importance as JSON")
        ->required();
    sub->add_option("--labels", a->labels,
                    "Write the voxel -> branch label map as NRRD, with a 3D Slicer colour table (.ctbl) beside it");
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    a->simplifiers.add_to(*sub, context, "Simplifier options");
    context.add_command(sub, [a, &context]() {
        if (!a->cut.keep && !a->cut.threshold)
            throw std::invalid_argument("give --keep N or --threshold T");
        PluginInstance &simplifier = a->simplifiers.resolve(a->simplifier);
        LoadedVolume in = a->input.load();
        a->filter.apply(in, context);
        topology::TopologyResult topo = run_contour_tree(in.volume, context);
        SimplifiedTree s = simplify_tree(topo.tree, in.volume, simplifier, a->cut, context);
        write_json(a->json, in, topo, s, a->cut);
        if (!a->labels.empty())
            io::write_label_map(a->labels, in.volume.geometry(), "arbor " + s.id + " labels of " + in.source,
                                topology::label_voxels(topo.tree, s.branches, s.cut),
                                kept_label_names(s.branches, s.cut));
        std::printf("%s: %zu branches, %zu kept by %s (%s) -> %s\n", in.source.c_str(), s.branches.branches.size(),
                    s.cut.kept.size(), s.id.c_str(), a->cut.describe().c_str(), a->json.c_str());
        if (a->timings) {
            topo.timings.push_back({"simplification", s.seconds});
            topo.total_seconds += s.seconds;
            topo.branches = std::move(s.branches); // for the branch count
            print_timings(topo, in.volume);
        }
        return 0;
    });
}

} // namespace arbor::cli
