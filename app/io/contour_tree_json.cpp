#include "contour_tree_json.hpp"

#include "json_writer.hpp"
#include "topology_json.hpp"

#include <cmath>

namespace arbor::io {

namespace {

using topology::BranchKind;
using topology::NodeKind;

// Kinds are written as small integers, indices into these names.
static_assert(static_cast<int>(NodeKind::Minimum) == 0 && static_cast<int>(NodeKind::Lone) == 5);
constexpr int kNodeKinds = 6;
static_assert(static_cast<int>(BranchKind::Root) == 0 && static_cast<int>(BranchKind::Minimum) == 2);
constexpr int kBranchKinds = 3;

void write_volume(JsonWriter &j, const ContourTreeFile &f)
{
    const Geometry &g = f.volume->geometry();
    const JsonWriter::Scope volume = j.object("volume");
    j.field("source", f.source);
    j.field("dims", g.dims);
    j.field("spacing_mm", g.spacing);
    j.field("origin_mm", g.origin);
    j.field("direction", g.direction);
    j.field("voxel_type", arbor_voxel_type_name(f.volume->type()));
    j.field("global_min", (*f.branches).global_min);
    j.field("global_max", (*f.branches).global_max);
}

void write_nodes(JsonWriter &j, const ContourTreeFile &f)
{
    const topology::ContourTree &t = (*f.tree);
    const Volume &vol = *f.volume;
    const JsonWriter::Scope nodes = j.object("nodes");
    j.column("kind_names", kNodeKinds,
             [](std::size_t k) { return topology::node_kind_name(static_cast<NodeKind>(k)); });
    j.field("vertex", t.node_vertex);
    j.column("kind", t.node_count(), [&](std::size_t x) { return static_cast<uint8_t>(t.node_kind[x]); });
    j.column("value", t.node_count(), [&](std::size_t x) { return vol.value(t.node_vertex[x]); });
    j.field("branch", (*f.branches).node_branch);
}

void write_arcs(JsonWriter &j, const ContourTreeFile &f)
{
    const topology::ContourTree &t = (*f.tree);
    const JsonWriter::Scope arcs = j.object("arcs");
    j.field("lower", t.arc_lo);
    j.field("upper", t.arc_hi);
    j.field("interior_voxels", topology::arc_interior_voxels(t));
    j.field("branch", (*f.branches).arc_branch);
}

void write_branches(JsonWriter &j, const ContourTreeFile &f)
{
    const auto &b = (*f.branches).branches;
    const std::size_t n = b.size();
    const JsonWriter::Scope branches = j.object("branches");
    j.column("kind_names", kBranchKinds, [](std::size_t k) { return branch_kind_name(static_cast<BranchKind>(k)); });
    j.column("kind", n, [&](std::size_t i) { return static_cast<uint8_t>(b[i].kind); });
    j.column("parent", n, [&](std::size_t i) { return b[i].parent; });
    j.column("depth", n, [&](std::size_t i) { return b[i].depth; });
    j.column("extremum_node", n, [&](std::size_t i) { return b[i].extremum_node; });
    j.column("saddle_node", n, [&](std::size_t i) { return b[i].saddle_node; });
    // The root's importance is infinite (it is never simplified away): 1.
    j.column("importance", n, [&](std::size_t i) { return std::isinf(b[i].importance) ? 1.0 : b[i].importance; });
    const JsonWriter::Scope measures = j.object("measures");
    for (int m = 0; m < topology::kMeasureCount; ++m)
        j.column(topology::measure_id(m), n, [&](std::size_t i) { return b[i].measures[static_cast<std::size_t>(m)]; });
}

void write_simplified(JsonWriter &j, const topology::SimplificationCut &cut)
{
    // Kept branch k has label k (the label map's value); its parent label
    // is that of its nearest kept ancestor.
    const JsonWriter::Scope simplified = j.object("simplified");
    const JsonWriter::Scope kept = j.object("kept_branches");
    j.field("branch", cut.kept);
    j.field("parent_label", cut.kept_parent);
}

} // namespace

void write_contour_tree_json(const std::filesystem::path &path, const ContourTreeFile &f)
{
    write_json_file(path, JsonLayout::compact, [&](JsonWriter &j) {
        j.field("format", "arbor-contour-tree/2");
        if (f.annotate)
            f.annotate(j);
        write_volume(j, f);
        write_nodes(j, f);
        write_arcs(j, f);
        write_branches(j, f);
        if (f.cut)
            write_simplified(j, *f.cut);
        const JsonWriter::Scope timings = j.object("timings_seconds");
        double total = 0;
        for (const topology::StageTiming &stage : *f.timings) {
            j.field(stage.stage, stage.seconds);
            total += stage.seconds;
        }
        j.field("total", total);
    });
}

} // namespace arbor::io
