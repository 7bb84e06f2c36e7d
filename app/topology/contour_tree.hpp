// contour_tree.hpp - the contour tree of a scalar field, merged from its
// augmented join and split trees (Carr, Snoeyink and Axen 2003), with its
// augmentation: the arc every voxel lies on.
//
// Nodes are the critical vertices (minima, maxima, join and split saddles;
// degenerate saddles keep their full degree); regular vertices are removed
// from the tree but keep their arc in `vertex_arc`, so the segmentation is
// never lost.  Every measure downstream (volume, hypervolume, labels) is
// accumulated from this augmentation instead of re-flooding the volume.
#pragma once

#include "../core/huge_pages.hpp"
#include "merge_tree.hpp"
#include "uninitialized_buffer.hpp"
#include "vertex_order.hpp"

#include <cstdint>

namespace arbor::topology {

inline constexpr uint32_t kNoArc = 0xffffffffu;

enum class NodeKind : uint8_t {
    Minimum,
    Maximum,
    JoinSaddle,  // two or more arcs below, one above
    SplitSaddle, // one arc below, two or more above
    Saddle,      // two or more arcs on both sides (degenerate)
    Lone,        // the only vertex of a one-voxel volume
};

const char *node_kind_name(NodeKind kind);

struct ContourTree {
    // Nodes in increasing simulated value (value, then vertex id): node 0 is
    // the global minimum, the last node the global maximum.
    HugeVector<uint32_t> node_vertex;
    HugeVector<uint8_t> node_up;   // arcs above the node
    HugeVector<uint8_t> node_down; // arcs below the node
    HugeVector<NodeKind> node_kind;
    // Arcs: lower and upper node index.  Arcs incident to a node are listed
    // in node_arc_offsets/node_arcs.
    HugeVector<uint32_t> arc_lo;
    HugeVector<uint32_t> arc_hi;
    HugeVector<uint32_t> node_arc_offsets; // [nodes + 1]
    HugeVector<uint32_t> node_arcs;
    // For every vertex id, the arc it lies on.  A node lies on several arcs;
    // it carries the arc by which the merge removed it (stable, but measures
    // count nodes on their own).  kNoArc for a one-voxel volume.
    UninitializedBuffer<uint32_t> vertex_arc;

    std::size_t node_count() const { return node_vertex.size(); }
    std::size_t arc_count() const { return arc_lo.size(); }
};

// Per arc, the voxels that lie inside it: those the augmentation puts on
// the arc, less the nodes (which are counted on their own).
HugeVector<uint32_t> arc_interior_voxels(const ContourTree &tree);

// Merges the two trees the sweeps left in `state` (jt_up, st_down and the
// degrees of every vertex by rank; see merge_tree.hpp), consuming it, the
// label words `labels` (4 bytes a vertex, whatever the sweeps left in them)
// and the order: `order`, the vertices lowest first (whole or streamed),
// names the grid vertex of each rank for the node list and the
// augmentation.  Work space beyond them: the tree itself; vertex_arc (4
// bytes a vertex) is written in place of the state's first third.
ContourTree merge_contour_tree(UninitializedBuffer<MergeVertex> state, UninitializedBuffer<uint32_t> labels,
                               OrderPieces order, const ProgressFn &progress = {});

} // namespace arbor::topology
