// merge_tree.hpp - the join tree and the split tree of a scalar field on the
// Freudenthal-triangulated grid, augmented (every vertex is in the tree), by
// union-find sweeps.
//
// The join tree sweeps vertices upwards and tracks the components of the
// sublevel set: a vertex with no lower neighbour starts a component (a
// minimum), a vertex whose lower neighbours lie in two or more components
// merges them (a join saddle).  The split tree does the same downwards with
// superlevel sets.  Each component remembers its most recently added vertex,
// so attaching a component to the current vertex is exactly the augmented
// tree's parent link.
//
// Per vertex the sweep keeps a bit (swept yet?) and the component the vertex
// joined.  The bits of the 14 neighbours say which pieces the lower link has
// (link_components.hpp); the component of one neighbour per piece is read,
// usually in the current vertex's own cache line, and union-find runs on
// components, whose links stay in cache.
#pragma once

#include "grid_neighbors.hpp"
#include "uninitialized_buffer.hpp"
#include "vertex_order.hpp"


#include <cstdint>

namespace arbor::topology {

inline constexpr uint32_t kNoVertex = 0xffffffffu;

struct MergeTree {
    // Vertex that next extended this vertex's component (join tree: a higher
    // vertex; split tree: a lower one); kNoVertex for the root (the global
    // maximum of the join tree, the global minimum of the split tree).
    UninitializedBuffer<uint32_t> parent;
    // Number of components this vertex merged: 0 for a leaf (a minimum of the
    // join tree, a maximum of the split tree), 1 for a regular vertex, >= 2 for
    // a saddle.  At most 14.
    UninitializedBuffer<uint8_t> children;
};

// Work space of one sweep: per vertex, the component it joined when the
// sweep passed it (4 bytes a vertex, read only once written).  Union-find runs
// on components, not vertices: there are as many as the tree has leaves, so
// their links stay in cache and a find costs no memory round trip.
struct SweepScratch {
    uint32_t *component;
};
inline constexpr std::size_t kSweepScratchBytes = 4;

// The two sweeps of the grid's vertices in the order `order` (sort_vertices:
// the order is all they need of the values).  Without scratch, each sweep
// allocates its own.
MergeTree compute_join_tree(const GridNeighbors &grid, const UninitializedBuffer<uint32_t> &order,
                            const ProgressFn &progress = {}, const SweepScratch *scratch = nullptr);
MergeTree compute_split_tree(const GridNeighbors &grid, const UninitializedBuffer<uint32_t> &order,
                             const ProgressFn &progress = {}, const SweepScratch *scratch = nullptr);

} // namespace arbor::topology
