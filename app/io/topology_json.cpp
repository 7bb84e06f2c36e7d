#include "topology_json.hpp"

namespace arbor::io {

std::array<double, 3> voxel_ijk(const Geometry &g, uint32_t v)
{
    return {static_cast<double>(v % g.dims[0]), static_cast<double>((v / g.dims[0]) % g.dims[1]),
            static_cast<double>(v / (g.dims[0] * g.dims[1]))};
}

void write_tree_point(JsonStream &j, const topology::ContourTree &t, const Volume &vol, uint32_t node)
{
    j.raw("{");
    j.key("node");
    j.number(node);
    j.raw(",");
    write_vertex_fields(j, vol, t.node_vertex[node]);
    j.raw("}");
}

void write_vertex_fields(JsonStream &j, const Volume &vol, uint32_t v)
{
    j.key("vertex");
    j.number(v);
    j.raw(",");
    j.key("ijk");
    j.triple(voxel_ijk(vol.geometry(), v));
    j.raw(",");
    j.key("position_mm");
    j.triple(vol.geometry().position_of(v));
    j.raw(",");
    j.key("value");
    j.number(vol.value(v));
}

void write_branch_ends_and_measures(JsonStream &j, const topology::ContourTree &t, const Volume &vol,
                                    const topology::BranchDecomposition &d, uint32_t branch)
{
    const topology::Branch &br = d.branches[branch];
    j.key("extremum");
    write_tree_point(j, t, vol, br.extremum_node);
    j.raw(",");
    j.key("saddle");
    write_tree_point(j, t, vol, br.saddle_node);
    j.raw(",");
    j.key("measures");
    write_measures(j, br.measures);
    j.raw(",");
    j.key("relative_measures");
    write_relative_measures(j, d, branch);
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

const char *branch_kind_name(topology::BranchKind k)
{
    switch (k) {
    case topology::BranchKind::Root: return "root";
    case topology::BranchKind::Maximum: return "maximum";
    case topology::BranchKind::Minimum: return "minimum";
    }
    return "?";
}

void write_relative_measures(JsonStream &j, const topology::BranchDecomposition &d, uint32_t branch)
{
    std::array<double, topology::kMeasureCount> relative;
    for (int m = 0; m < topology::kMeasureCount; ++m)
        relative[static_cast<std::size_t>(m)] = d.relative(branch, m);
    write_measures(j, relative);
}

void write_contour_tree_summary(JsonStream &j, const topology::ContourTree &tree, double seconds,
                                std::optional<std::size_t> branches)
{
    j.key("contour_tree");
    j.raw("{");
    j.key("nodes");
    j.number(static_cast<double>(tree.node_count()));
    j.raw(",");
    j.key("arcs");
    j.number(static_cast<double>(tree.arc_count()));
    j.raw(",");
    j.key("seconds");
    j.number(seconds);
    if (branches) {
        j.raw(",");
        j.key("branches");
        j.number(static_cast<double>(*branches));
    }
    j.raw("}");
}

void write_volume_summary(JsonStream &j, const std::string &source, const Geometry &g)
{
    j.key("volume");
    j.raw("{");
    j.key("source");
    j.string(source);
    j.raw(",");
    j.key("dims");
    j.triple({static_cast<double>(g.dims[0]), static_cast<double>(g.dims[1]), static_cast<double>(g.dims[2])});
    j.raw(",");
    j.key("spacing_mm");
    j.triple(g.spacing);
    j.raw("}");
}

} // namespace arbor::io
