// merge_tree.hpp - the join tree and the split tree of a scalar field on the
// Freudenthal-triangulated grid, augmented (every vertex is in the tree), by
// union-find sweeps.
//
// The join tree sweeps vertices upwards and tracks the components of the
// sublevel set: a vertex with no lower neighbour starts a component (a
// minimum), a vertex whose lower neighbours lie in two or more components
// merges them (a join saddle).  The split tree does the same downwards with
// superlevel sets.  Union-find keeps the most recently added vertex as the
// root of each component, so attaching a component to the current vertex is
// exactly the augmented tree's parent link.
//
// Arrays are indexed by vertex id and "lower" is decided from the values
// themselves (simulation of simplicity: value, then id), so a sweep touches
// only the neighbourhood of the current vertex, which is close in memory.
#pragma once

#include "grid_neighbors.hpp"
#include "uninitialized_buffer.hpp"
#include "vertex_order.hpp"

#include <arbor/volume.h>

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

// Work space of one sweep, one entry per vertex: union-find parents, the
// newest vertex of each component, union-by-rank heights (9 bytes a vertex).
// The pipeline lends the same memory to the merge afterwards, so it is
// faulted in once.
struct SweepScratch {
    uint32_t *uf;
    uint32_t *top;
    uint8_t *height;
};
inline constexpr std::size_t kSweepScratchBytes = 9;

// The two sweeps over `values` (voxel type `type`) in the order `order`.
// Without scratch, each sweep allocates its own.
MergeTree compute_join_tree(const GridNeighbors &grid, arbor_voxel_type type, const void *values,
                            const UninitializedBuffer<uint32_t> &order, const ProgressFn &progress = {},
                            const SweepScratch *scratch = nullptr);
MergeTree compute_split_tree(const GridNeighbors &grid, arbor_voxel_type type, const void *values,
                             const UninitializedBuffer<uint32_t> &order, const ProgressFn &progress = {},
                             const SweepScratch *scratch = nullptr);

} // namespace arbor::topology
