#include "topology_json.hpp"

#include <cmath>

namespace arbor::io {

std::array<int64_t, 3> voxel_ijk(const Geometry &g, uint32_t v)
{
    return {v % g.dims[0], (v / g.dims[0]) % g.dims[1], v / (g.dims[0] * g.dims[1])};
}

void write_vertex_fields(JsonWriter &j, const Volume &vol, uint32_t v)
{
    j.field("vertex", v);
    j.field("ijk", voxel_ijk(vol.geometry(), v));
    j.field("position_mm", vol.geometry().position_of(v));
    j.field("value", vol.value(v));
}

void write_tree_point(JsonWriter &j, std::string_view key, const topology::ContourTree &t, const Volume &vol,
                      uint32_t node)
{
    const JsonWriter::Scope point = j.object(key);
    j.field("node", node);
    write_vertex_fields(j, vol, t.node_vertex[node]);
}

void write_branch_ends_and_measures(JsonWriter &j, const topology::ContourTree &t, const Volume &vol,
                                    const topology::BranchDecomposition &d, uint32_t branch)
{
    const topology::Branch &br = d.branches[branch];
    write_tree_point(j, "extremum", t, vol, br.extremum_node);
    write_tree_point(j, "saddle", t, vol, br.saddle_node);
    write_measures(j, "measures", br.measures);
    write_relative_measures(j, "relative_measures", d, branch);
}

void write_measures(JsonWriter &j, std::string_view key, const std::array<double, topology::kMeasureCount> &m)
{
    const JsonWriter::Scope measures = j.object(key);
    for (int i = 0; i < topology::kMeasureCount; ++i)
        j.field(topology::measure_id(i), m[static_cast<std::size_t>(i)]);
}

const char *branch_kind_name(topology::BranchKind k)
{
    switch (k) {
    case topology::BranchKind::Root: return "root";
    case topology::BranchKind::Maximum: return "maximum";
    case topology::BranchKind::Minimum: return "minimum";
    }
    return "?";
}

void write_relative_measures(JsonWriter &j, std::string_view key, const topology::BranchDecomposition &d,
                             uint32_t branch)
{
    std::array<double, topology::kMeasureCount> relative;
    for (int m = 0; m < topology::kMeasureCount; ++m)
        relative[static_cast<std::size_t>(m)] = d.relative(branch, m);
    write_measures(j, key, relative);
}

void write_contour_tree_summary(JsonWriter &j, const topology::ContourTree &tree, double seconds,
                                std::optional<std::size_t> branches)
{
    const JsonWriter::Scope summary = j.object("contour_tree");
    j.field("nodes", tree.node_count());
    j.field("arcs", tree.arc_count());
    j.field("seconds", seconds);
    if (branches)
        j.field("branches", *branches);
}

void write_volume_summary(JsonWriter &j, const std::string &source, const Geometry &g)
{
    const JsonWriter::Scope volume = j.object("volume");
    j.field("source", source);
    j.field("dims", g.dims);
    j.field("spacing_mm", g.spacing);
}

std::vector<uint32_t> kept_depths(const topology::SimplificationCut &cut)
{
    std::vector<uint32_t> depth(cut.kept.size(), 0);
    for (std::size_t k = 1; k < cut.kept.size(); ++k)
        depth[k] = depth[static_cast<std::size_t>(cut.kept_parent[k])] + 1; // parents come first
    return depth;
}

void write_kept_branches(JsonWriter &j, std::string_view key, const topology::ContourTree &tree, const Volume &volume,
                         const topology::BranchDecomposition &d, const topology::SimplificationCut &cut)
{
    const std::vector<uint32_t> depth = kept_depths(cut);
    const JsonWriter::Scope kept = j.array(key);
    for (std::size_t k = 0; k < cut.kept.size(); ++k) {
        const uint32_t b = cut.kept[k];
        const topology::Branch &br = d.branches[b];
        const JsonWriter::Scope o = j.object();
        j.field("label", k);
        j.field("branch", b);
        j.field("parent_label", cut.kept_parent[k]);
        j.field("kind", branch_kind_name(br.kind));
        j.field("depth", depth[k]);
        j.field("importance", std::isinf(br.importance) ? 1.0 : br.importance);
        write_branch_ends_and_measures(j, tree, volume, d, b);
    }
}

} // namespace arbor::io
