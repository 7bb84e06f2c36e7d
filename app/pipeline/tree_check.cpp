#include "tree_check.hpp"

#include <cstddef>

namespace arbor::pipeline {

namespace {

using topology::ContourTree;
using topology::NodeKind;

std::string str(uint64_t value)
{
    return std::to_string(value);
}

// The kind a node of these degrees has (the definitions in contour_tree.hpp).
NodeKind expected_kind(unsigned up, unsigned down)
{
    if (up == 0 && down == 0)
        return NodeKind::Lone;
    if (down == 0)
        return NodeKind::Minimum;
    if (up == 0)
        return NodeKind::Maximum;
    if (up >= 2 && down >= 2)
        return NodeKind::Saddle;
    return down >= 2 ? NodeKind::JoinSaddle : NodeKind::SplitSaddle;
}

std::string check_sizes(const ContourTree &t, uint64_t vertex_count)
{
    const uint64_t nodes = t.node_vertex.size(), arcs = t.arc_lo.size();
    if (vertex_count == 0)
        return "the tree is of an empty volume";
    if (vertex_count > UINT32_MAX)
        return "the tree has " + str(vertex_count) + " vertices; vertex ids are 32-bit";
    if (t.vertex_arc.size() != vertex_count)
        return "the segmentation has " + str(t.vertex_arc.size()) + " entries for " + str(vertex_count) +
               " vertices";
    if (nodes == 0 || nodes > vertex_count)
        return "the tree has " + str(nodes) + " nodes for " + str(vertex_count) + " vertices";
    if (arcs + 1 != nodes)
        return "the tree has " + str(nodes) + " nodes and " + str(arcs) + " arcs; a tree has one arc fewer than nodes";
    if (t.node_up.size() != nodes || t.node_down.size() != nodes || t.node_kind.size() != nodes)
        return "the node degrees or kinds are not one per node";
    if (t.arc_hi.size() != arcs)
        return "the arcs' lower and upper nodes differ in number";
    if (t.node_arc_offsets.size() != nodes + 1)
        return "the incidence offsets are not one per node plus one";
    if (t.node_arcs.size() != 2 * arcs)
        return "the incidence lists hold " + str(t.node_arcs.size()) + " entries for " + str(arcs) +
               " arcs (two each)";
    return {};
}

std::string check_arcs(const ContourTree &t)
{
    const uint64_t nodes = t.node_vertex.size();
    for (std::size_t a = 0; a < t.arc_lo.size(); ++a) {
        const uint32_t lo = t.arc_lo[a], hi = t.arc_hi[a];
        if (lo >= nodes || hi >= nodes)
            return "arc " + str(a) + " joins nodes " + str(lo) + " and " + str(hi) + ", but the tree has " +
                   str(nodes) + " nodes";
        if (lo >= hi)
            return "arc " + str(a) + " does not run upwards (from node " + str(lo) + " to node " + str(hi) + ")";
    }
    return {};
}

std::string check_nodes(const ContourTree &t, uint64_t vertex_count)
{
    const std::size_t nodes = t.node_vertex.size();
    const uint64_t arcs = t.arc_lo.size();
    const auto &offsets = t.node_arc_offsets;
    if (offsets[0] != 0)
        return "the incidence offsets start at " + str(offsets[0]) + ", not 0";
    if (offsets[nodes] != t.node_arcs.size())
        return "the incidence offsets end at " + str(offsets[nodes]) + ", not at the " + str(t.node_arcs.size()) +
               " entries of the lists";
    // Monotone from 0 to the lists' size: every list lies within node_arcs.
    for (std::size_t i = 0; i < nodes; ++i)
        if (offsets[i + 1] < offsets[i])
            return "the incidence offsets are not monotone at node " + str(i) + " (" + str(offsets[i]) + " then " +
                   str(offsets[i + 1]) + ")";
    for (std::size_t i = 0; i < nodes; ++i) {
        if (t.node_vertex[i] >= vertex_count)
            return "node " + str(i) + " lies on vertex " + str(t.node_vertex[i]) + ", but the volume has " +
                   str(vertex_count) + " vertices";
        unsigned up = 0, down = 0;
        for (uint32_t k = offsets[i]; k < offsets[i + 1]; ++k) {
            const uint32_t a = t.node_arcs[k];
            if (a >= arcs)
                return "node " + str(i) + " lists arc " + str(a) + ", but the tree has " + str(arcs) + " arcs";
            if (t.arc_lo[a] == i)
                ++up;
            else if (t.arc_hi[a] == i)
                ++down;
            else
                return "node " + str(i) + " lists arc " + str(a) + ", which does not touch it";
        }
        if (up != t.node_up[i] || down != t.node_down[i])
            return "node " + str(i) + " has " + str(up) + " arcs above and " + str(down) + " below, but records " +
                   str(t.node_up[i]) + " and " + str(t.node_down[i]);
        if (t.node_kind[i] != expected_kind(up, down))
            return "node " + str(i) + " has kind " + str(static_cast<unsigned>(t.node_kind[i])) +
                   ", which does not match its " + str(up) + " arcs above and " + str(down) + " below";
    }
    return {};
}

std::string check_segmentation(const ContourTree &t)
{
    const uint32_t arcs = static_cast<uint32_t>(t.arc_lo.size());
    const uint32_t *arc = t.vertex_arc.data();
    const std::size_t n = t.vertex_arc.size();
    // A branch-free pass first (the common, valid case); the position of a bad
    // entry is only searched for when there is one.
    bool bad = false;
    for (std::size_t v = 0; v < n; ++v)
        bad |= arc[v] >= arcs && arc[v] != topology::kNoArc;
    if (!bad)
        return {};
    for (std::size_t v = 0; v < n; ++v)
        if (arc[v] >= arcs && arc[v] != topology::kNoArc)
            return "vertex " + str(v) + " lies on arc " + str(arc[v]) + ", but the tree has " + str(arcs) + " arcs";
    return {};
}

} // namespace

std::string find_tree_defect(const ContourTree &tree, uint64_t vertex_count)
{
    std::string defect = check_sizes(tree, vertex_count);
    if (defect.empty())
        defect = check_arcs(tree);
    if (defect.empty())
        defect = check_nodes(tree, vertex_count);
    if (defect.empty())
        defect = check_segmentation(tree);
    return defect;
}

} // namespace arbor::pipeline
