// link_components.hpp - the connected components of part of a vertex's link
// in the Freudenthal triangulation, by table lookup.
//
// The link of a grid vertex is a triangulated sphere on its 14 neighbours
// (a disk on the boundary).  Two neighbours of v that are both below v and
// joined by a link edge lie in one component of the sublevel set below v:
// the edge between them was seen when the later of the two was swept.  So a
// merge-tree sweep needs the component of only one neighbour per connected
// piece of the lower link; which neighbours those are depends only on the
// 14-bit set of lower neighbours, and a 2^14-entry table answers it.  A piece
// of the link is at most 6 components (checked when the table is built).
#pragma once

#include "grid_neighbors.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace arbor::topology {

struct LinkComponents {
    uint8_t count = 0;
    // One neighbour index per component, the lowest index in it: in-row
    // neighbours (indices 0 and 1) come first, so the representative is in
    // the vertex's own cache line whenever it can be.
    std::array<uint8_t, 6> first{};
};

// The table, indexed by the set of neighbours (bit n: kFreudenthalOffsets[n]).
const std::vector<LinkComponents> &link_components_table();

} // namespace arbor::topology
