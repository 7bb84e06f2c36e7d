// `arbor tree <volume> --json out.json`: the contour tree (nodes, arcs) and
// its persistence branch decomposition with every branch's measures; with
// --keep/--threshold also the simplified hierarchy and its voxel labels.
#include "commands.hpp"
#include "simplification_run.hpp"
#include "topology_run.hpp"
#include "filter_input.hpp"
#include "volume_input.hpp"

#include "io/label_map_output.hpp"
#include "io/topology_json.hpp"
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
    io::write_json_file(path, io::JsonLayout::compact, [&](io::JsonWriter &j) {
        j.field("format", "arbor-contour-tree/1");
        {
            const io::JsonWriter::Scope volume = j.object("volume");
            j.field("source", in.source);
            j.field("dims", vol.geometry().dims);
            j.field("voxel_type", arbor_voxel_type_name(vol.type()));
            j.field("global_min", d.global_min);
            j.field("global_max", d.global_max);
        }
        {
            const io::JsonWriter::Scope nodes = j.array("nodes");
            for (std::size_t x = 0; x < t.node_count(); ++x) {
                const io::JsonWriter::Scope node = j.object();
                j.field("id", x);
                j.field("kind", topology::node_kind_name(t.node_kind[x]));
                io::write_vertex_fields(j, vol, t.node_vertex[x]);
                j.field("branch", d.node_branch[x]);
            }
        }
        std::vector<double> arc_voxels(t.arc_count(), 0.0);
        for (std::size_t v = 0; v < t.vertex_arc.size(); ++v)
            if (t.vertex_arc[v] != topology::kNoArc)
                arc_voxels[t.vertex_arc[v]] += 1.0;
        for (uint32_t v : t.node_vertex)
            if (t.vertex_arc[v] != topology::kNoArc)
                arc_voxels[t.vertex_arc[v]] -= 1.0; // nodes are not interior voxels
        {
            const io::JsonWriter::Scope arcs = j.array("arcs");
            for (std::size_t a = 0; a < t.arc_count(); ++a) {
                const io::JsonWriter::Scope arc = j.object();
                j.field("id", a);
                j.field("lower", t.arc_lo[a]);
                j.field("upper", t.arc_hi[a]);
                j.field("interior_voxels", arc_voxels[a]);
                j.field("branch", d.arc_branch[a]);
            }
        }
        {
            const io::JsonWriter::Scope branches = j.array("branches");
            for (std::size_t b = 0; b < d.branches.size(); ++b) {
                const topology::Branch &br = d.branches[b];
                const io::JsonWriter::Scope branch = j.object();
                j.field("id", b);
                j.field("kind", io::branch_kind_name(br.kind));
                j.field("parent", br.parent);
                j.field("depth", br.depth);
                j.field("children", d.children(static_cast<uint32_t>(b)));
                io::write_branch_ends_and_measures(j, t, vol, d, static_cast<uint32_t>(b));
                j.field("importance", std::isinf(br.importance) ? 1.0 : br.importance);
                if (cut)
                    j.field("kept", cut->kept_index[b] >= 0);
            }
        }
        if (cut) {
            const io::JsonWriter::Scope simplified = j.object("simplified");
            const io::JsonWriter::Scope kept = j.array("kept_branches");
            for (std::size_t k = 0; k < cut->kept.size(); ++k) {
                const io::JsonWriter::Scope o = j.object();
                j.field("label", k);
                j.field("branch", cut->kept[k]);
                j.field("parent_label", cut->kept_parent[k]);
            }
        }
        const io::JsonWriter::Scope timings = j.object("timings_seconds");
        for (const topology::StageTiming &stage : topo.timings)
            j.field(stage.stage, stage.seconds);
        j.field("total", topo.total_seconds);
    });
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
