// `arbor tree <volume> --json out.json`: the contour tree (nodes, arcs) and
// its persistence branch decomposition with every branch's measures; with
// --keep/--threshold also the simplified hierarchy and its voxel labels.
#include "commands.hpp"
#include "io/topology_json.hpp"
#include "io/label_map_output.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "topology/simplification.hpp"

#include <cmath>
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

void write_json(const std::string &path, const LoadedVolume &in, const topology::TopologyResult &topo,
                const topology::SimplificationCut *cut)
{
    const topology::ContourTree &t = topo.tree;
    const topology::BranchDecomposition &d = topo.branches;
    const Volume &vol = in.volume;
    AtomicFile file(path);
    io::JsonStream j(file);
    j.raw("{\n");
    j.key("format");
    j.string("arbor-contour-tree/1");
    j.raw(",\n");
    j.key("volume");
    j.raw("{");
    j.key("source");
    j.string(in.source);
    j.raw(",");
    j.key("dims");
    j.triple({static_cast<double>(vol.geometry().dims[0]), static_cast<double>(vol.geometry().dims[1]),
              static_cast<double>(vol.geometry().dims[2])});
    j.raw(",");
    j.key("voxel_type");
    j.string(arbor_voxel_type_name(vol.type()));
    j.raw(",");
    j.key("global_min");
    j.number(d.global_min);
    j.raw(",");
    j.key("global_max");
    j.number(d.global_max);
    j.raw("},\n");

    j.key("nodes");
    j.raw("[\n");
    for (std::size_t x = 0; x < t.node_count(); ++x) {
        j.raw(x ? ",\n{" : "{");
        j.key("id");
        j.number(static_cast<double>(x));
        j.raw(",");
        j.key("kind");
        j.string(topology::node_kind_name(t.node_kind[x]));
        j.raw(",");
        io::write_vertex_fields(j, vol, t.node_vertex[x]);
        j.raw(",");
        j.key("branch");
        j.number(d.node_branch[x]);
        j.raw("}");
    }
    j.raw("\n],\n");

    std::vector<double> arc_voxels(t.arc_count(), 0.0);
    for (std::size_t v = 0; v < t.vertex_arc.size(); ++v)
        if (t.vertex_arc[v] != topology::kNoArc)
            arc_voxels[t.vertex_arc[v]] += 1.0;
    for (uint32_t v : t.node_vertex)
        if (t.vertex_arc[v] != topology::kNoArc)
            arc_voxels[t.vertex_arc[v]] -= 1.0; // nodes are not interior voxels
    j.key("arcs");
    j.raw("[\n");
    for (std::size_t a = 0; a < t.arc_count(); ++a) {
        j.raw(a ? ",\n{" : "{");
        j.key("id");
        j.number(static_cast<double>(a));
        j.raw(",");
        j.key("lower");
        j.number(t.arc_lo[a]);
        j.raw(",");
        j.key("upper");
        j.number(t.arc_hi[a]);
        j.raw(",");
        j.key("interior_voxels");
        j.number(arc_voxels[a]);
        j.raw(",");
        j.key("branch");
        j.number(d.arc_branch[a]);
        j.raw("}");
    }
    j.raw("\n],\n");

    j.key("branches");
    j.raw("[\n");
    for (std::size_t b = 0; b < d.branches.size(); ++b) {
        const topology::Branch &br = d.branches[b];
        j.raw(b ? ",\n{" : "{");
        j.key("id");
        j.number(static_cast<double>(b));
        j.raw(",");
        j.key("kind");
        j.string(io::branch_kind_name(br.kind));
        j.raw(",");
        j.key("parent");
        j.number(br.parent);
        j.raw(",");
        j.key("depth");
        j.number(br.depth);
        j.raw(",");
        j.key("children");
        j.raw("[");
        for (const uint32_t c : d.children(static_cast<uint32_t>(b))) {
            if (c != d.child_offsets[b])
                j.raw(",");
            j.number(c);
        }
        j.raw("],");
        io::write_branch_ends_and_measures(j, t, vol, d, static_cast<uint32_t>(b));
        j.raw(",");
        j.key("importance");
        j.number(std::isinf(br.importance) ? 1.0 : br.importance);
        if (cut) {
            j.raw(",");
            j.key("kept");
            j.raw(cut->kept_index[b] >= 0 ? "true" : "false");
        }
        j.raw("}");
    }
    j.raw("\n]");

    if (cut) {
        j.raw(",\n");
        j.key("simplified");
        j.raw("{");
        j.key("kept_branches");
        j.raw("[");
        for (std::size_t k = 0; k < cut->kept.size(); ++k) {
            if (k)
                j.raw(",");
            j.raw("{");
            j.key("label");
            j.number(static_cast<double>(k));
            j.raw(",");
            j.key("branch");
            j.number(cut->kept[k]);
            j.raw(",");
            j.key("parent_label");
            j.number(cut->kept_parent[k]);
            j.raw("}");
        }
        j.raw("]}");
    }
    j.raw(",\n");
    j.key("timings_seconds");
    j.raw("{");
    for (std::size_t i = 0; i < topo.timings.size(); ++i) {
        if (i)
            j.raw(",");
        j.key(topo.timings[i].stage.c_str());
        j.number(topo.timings[i].seconds);
    }
    j.raw(",");
    j.key("total");
    j.number(topo.total_seconds);
    j.raw("}\n}\n");
    file.commit();
}

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
        write_json(a->json, in, topo, cut ? &*cut : nullptr);
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
