// merge_tree.hpp - the join tree and the split tree of a scalar field on the
// Freudenthal-triangulated grid, augmented (every vertex is in the tree), by
// union-find sweeps, written straight into the state the contour-tree merge
// works on.
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
#include "order_pieces.hpp"

#include <cstdint>

namespace arbor::topology {

inline constexpr uint32_t kNoVertex = 0xffffffffu;

// What the sweeps and then the contour-tree merge keep per vertex, packed in
// 16 bytes so that one cache line serves every access to a vertex.
struct MergeVertex {
    // Join tree: the vertex that next extended this vertex's component (a
    // higher one); kNoVertex for the global maximum.
    uint32_t jt_up;
    // Split tree: the same downwards; kNoVertex for the global minimum.
    uint32_t st_down;
    // The merge's arc; during a sweep, the component the vertex joined.
    uint32_t label;
    // Components the vertex merged in each tree: 0 for a leaf, 1 for a
    // regular vertex, >= 2 for a saddle (at most 14).  The merge marks a
    // removed vertex by jt_deg = 0xff.
    uint8_t jt_deg;
    uint8_t st_deg;
    // The merge's contour-tree degrees so far.
    uint8_t cnt_up;
    uint8_t cnt_down;
};
static_assert(sizeof(MergeVertex) == 16);

// Sweeps of the grid's vertices in the order `order` (whole or streamed:
// the order is all they need of the values).  The join sweep fills jt_up and
// jt_deg, the split sweep st_down and st_deg; neither touches the other's
// fields, so two threads may fill one state.  Each keeps the component of
// every vertex in `component` (4 bytes a vertex) or, when that is nullptr,
// in the state's `label`, which only one sweep at a time may do.
void compute_join_tree(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state, uint32_t *component,
                       const ProgressFn &progress = {});
void compute_split_tree(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state, uint32_t *component,
                        const ProgressFn &progress = {});

} // namespace arbor::topology
