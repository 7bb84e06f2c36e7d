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

// What the sweeps and then the contour-tree merge keep per vertex, indexed
// by the vertex's rank in the order (its position in the sweep), not by its
// grid index: a sweep then writes the state front to back (or back to front),
// and the merge's passes, which walk the order, read it as a stream.  Links
// are ranks too.  12 bytes; the merge's label words (4 bytes a vertex) are a
// separate array, which the sweeps use first, indexed by grid vertex, for
// their components (a neighbour's component is looked up by its grid index).
struct MergeVertex {
    // Join tree: the rank of the vertex that next extended this vertex's
    // component (a higher one); kNoVertex for the global maximum.
    uint32_t jt_up;
    // Split tree: the same downwards; kNoVertex for the global minimum.
    uint32_t st_down;
    // Components the vertex merged in each tree: 0 for a leaf, 1 for a
    // regular vertex, >= 2 for a saddle (at most 14).  The merge marks a
    // removed vertex by jt_deg = 0xff.
    uint8_t jt_deg;
    uint8_t st_deg;
    // The merge's contour-tree degrees so far.
    uint8_t cnt_up;
    uint8_t cnt_down;
};
static_assert(sizeof(MergeVertex) == 12);

// Sweeps of the grid's vertices in the order `order` (whole or streamed:
// the order is all they need of the values), into `state`, indexed by rank.
// The join sweep fills jt_up and jt_deg, the split sweep st_down and st_deg;
// neither touches the other's fields, so two threads may fill one state.
// Each keeps the component of every vertex, by grid index, in `component`
// (4 bytes a vertex): two sweeps at once need an array each; one after the
// other may share one (the merge's label words).
void compute_join_tree(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state, uint32_t *component,
                       const ProgressFn &progress = {});
void compute_split_tree(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state, uint32_t *component,
                        const ProgressFn &progress = {});

} // namespace arbor::topology
