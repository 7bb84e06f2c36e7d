// `arbor tree <volume> --json out.json`: the contour tree (nodes, arcs) and
// its persistence branch decomposition with every branch's measures; with
// --keep/--threshold also the simplified hierarchy and its voxel labels.
#include "commands.hpp"
#include "topology_run.hpp"
#include "volume_input.hpp"

#include "core/atomic_file.hpp"
#include "core/nrrd_writer.hpp"
#include "topology/simplification.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace arbor::cli {

namespace {

struct TreeArgs {
    VolumeInput input;
    std::string json;
    std::string labels;
    std::optional<std::size_t> keep;
    std::optional<double> threshold;
    bool timings = false;
};

// Streams JSON: trees of noisy scans have millions of nodes, too many to
// build as one document in memory first.
class JsonStream {
public:
    explicit JsonStream(AtomicFile &out) : out_(out) {}
    void raw(const std::string &s) { out_.write(s); }
    void number(double x)
    {
        if (!std::isfinite(x)) {
            raw("null");
            return;
        }
        char buf[40];
        if (x == std::floor(x) && std::fabs(x) < 1e15)
            std::snprintf(buf, sizeof buf, "%.0f", x);
        else
            std::snprintf(buf, sizeof buf, "%.17g", x);
        raw(buf);
    }
    void string(const std::string &s) { raw(nlohmann::json(s).dump()); }
    void key(const char *k)
    {
        string(k);
        raw(":");
    }
    void triple(const std::array<double, 3> &p)
    {
        raw("[");
        for (int i = 0; i < 3; ++i) {
            if (i)
                raw(",");
            number(p[i]);
        }
        raw("]");
    }

private:
    AtomicFile &out_;
};

std::array<double, 3> ijk(const Geometry &g, uint32_t v)
{
    return {static_cast<double>(v % g.dims[0]), static_cast<double>((v / g.dims[0]) % g.dims[1]),
            static_cast<double>(v / (g.dims[0] * g.dims[1]))};
}

void write_point(JsonStream &j, const topology::ContourTree &t, const Volume &vol, uint32_t node)
{
    const uint32_t v = t.node_vertex[node];
    j.raw("{");
    j.key("node");
    j.number(node);
    j.raw(",");
    j.key("vertex");
    j.number(v);
    j.raw(",");
    j.key("ijk");
    j.triple(ijk(vol.geometry(), v));
    j.raw(",");
    j.key("position_mm");
    j.triple(vol.geometry().position_of(v));
    j.raw(",");
    j.key("value");
    j.number(vol.value(v));
    j.raw("}");
}

void write_measures(JsonStream &j, const std::array<double, topology::kMeasureCount> &m)
{
    j.raw("{");
    for (int i = 0; i < topology::kMeasureCount; ++i) {
        if (i)
            j.raw(",");
        j.key(topology::measure_id(i));
        j.number(m[static_cast<std::size_t>(i)]);
    }
    j.raw("}");
}

const char *kind_name(topology::BranchKind k)
{
    switch (k) {
    case topology::BranchKind::Root: return "root";
    case topology::BranchKind::Maximum: return "maximum";
    case topology::BranchKind::Minimum: return "minimum";
    }
    return "?";
}

void write_json(const std::string &path, const LoadedVolume &in, const topology::TopologyResult &topo,
                const topology::SimplificationCut *cut)
{
    const topology::ContourTree &t = topo.tree;
    const topology::BranchDecomposition &d = topo.branches;
    const Volume &vol = in.volume;
    AtomicFile file(path);
    JsonStream j(file);
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
        const uint32_t v = t.node_vertex[x];
        j.raw(x ? ",\n{" : "{");
        j.key("id");
        j.number(static_cast<double>(x));
        j.raw(",");
        j.key("kind");
        j.string(topology::node_kind_name(t.node_kind[x]));
        j.raw(",");
        j.key("vertex");
        j.number(v);
        j.raw(",");
        j.key("ijk");
        j.triple(ijk(vol.geometry(), v));
        j.raw(",");
        j.key("position_mm");
        j.triple(vol.geometry().position_of(v));
        j.raw(",");
        j.key("value");
        j.number(vol.value(v));
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
        j.string(kind_name(br.kind));
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
        j.key("extremum");
        write_point(j, t, vol, br.extremum_node);
        j.raw(",");
        j.key("saddle");
        write_point(j, t, vol, br.saddle_node);
        j.raw(",");
        j.key("measures");
        write_measures(j, br.measures);
        j.raw(",");
        j.key("relative_measures");
        std::array<double, topology::kMeasureCount> relative;
        for (int m = 0; m < topology::kMeasureCount; ++m)
            relative[m] = d.relative(static_cast<uint32_t>(b), m);
        write_measures(j, relative);
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

void write_labels(const std::string &path, const LoadedVolume &in, const std::vector<uint32_t> &labels,
                  std::size_t label_count)
{
    const bool wide = label_count > 65535;
    Volume v = Volume::allocate(wide ? ARBOR_VOXEL_U32 : ARBOR_VOXEL_U16, in.volume.geometry(), {},
                                uint64_t{1} << 40);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (wide)
            v.as<uint32_t>()[i] = labels[i];
        else
            v.as<uint16_t>()[i] = static_cast<uint16_t>(labels[i]);
    }
    NrrdWriteOptions w;
    w.content = "arbor branch labels of " + in.source;
    w.key_values = {{"arbor_labels", std::to_string(label_count)}};
    write_nrrd(v, path, w);
}

} // namespace

void add_tree_command(CLI::App &app, Context &context)
{
    CLI::App *sub = app.add_subcommand(
        "tree", "Compute the contour tree and its branch decomposition (persistence) with measures");
    auto a = std::make_shared<TreeArgs>();
    a->input.add_to(*sub, context);
    sub->add_option("--json", a->json, "Write nodes, arcs and branches with measures as JSON")->required();
    auto *keep = sub->add_option("--keep", a->keep, "Also cut the hierarchy to the N most important branches")
                     ->check(CLI::PositiveNumber);
    auto *threshold = sub->add_option("--threshold", a->threshold,
                                      "Also cut the hierarchy at this relative persistence, in [0, 1]")
                          ->check(CLI::Range(0.0, 1.0));
    keep->excludes(threshold);
    sub->add_option("--labels", a->labels, "With --keep/--threshold: write the voxel -> branch labels (NRRD)");
    sub->add_flag("--timings", a->timings, "Print per-stage seconds and peak memory on stderr");
    context.add_command(sub, [a, &context]() {
        if (!a->labels.empty() && !a->keep && !a->threshold)
            throw std::invalid_argument("--labels needs --keep or --threshold");
        const LoadedVolume in = a->input.load();
        const topology::TopologyResult topo = run_topology(in.volume, topology::persistence_importance(), context);
        std::optional<topology::SimplificationCut> cut;
        if (a->keep)
            cut = topology::cut_by_count(topo.branches, *a->keep);
        else if (a->threshold)
            cut = topology::cut_by_threshold(topo.branches, *a->threshold);
        write_json(a->json, in, topo, cut ? &*cut : nullptr);
        if (cut && !a->labels.empty())
            write_labels(a->labels, in, topology::label_voxels(topo.tree, topo.branches, *cut), cut->kept.size());
        std::printf("%s: %zu nodes, %zu arcs, %zu branches%s -> %s\n", in.source.c_str(),
                    topo.tree.node_count(), topo.tree.arc_count(), topo.branches.branches.size(),
                    cut ? (", " + std::to_string(cut->kept.size()) + " kept").c_str() : "", a->json.c_str());
        if (a->timings)
            print_timings(topo, in.volume);
        return 0;
    });
}

} // namespace arbor::cli
