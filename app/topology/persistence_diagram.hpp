// persistence_diagram.hpp - a persistence diagram as the distances between
// diagrams see it: points (birth, death) with their homology dimension, and
// the essential ones (classes that never die) marked.
//
// From the contour tree's saddle-extremum pairs (persistence_pairs.hpp):
//   type 0  (minimum, join saddle)    dimension 0 (a component of a sublevel set)
//   type 2  (split saddle, maximum)   dimension d - 1 on a d-dimensional grid
//                                     (2 for a volume, 1 for a single slice)
//   type -1 (global minimum, global maximum) dimension 0, essential: the
//           component of the whole domain, born at the global minimum, which
//           never dies; as in TTK its point is drawn at death = global maximum,
//           so it has a finite position and is matched by that position.
#pragma once

#include "core/volume.hpp"
#include "persistence_pairs.hpp"

#include <vector>

namespace arbor::topology {

struct DiagramPoint {
    double birth = 0.0, death = 0.0; // death >= birth
    int dimension = 0;
    bool essential = false;
    double persistence() const { return death - birth; }
};

struct PersistenceDiagram {
    std::vector<DiagramPoint> points;
};

// The axes with more than one sample (1 to 3; 3 for an empty grid).
int grid_dimension(const Geometry &grid);

// Homology dimension of a pair of persistence_pairs.hpp's `type` on a grid of
// `grid_dimension` axes; throws std::invalid_argument for an unknown type.
int pair_dimension(int pair_type, int grid_dimension);

PersistenceDiagram diagram_of_pairs(const std::vector<PersistencePair> &pairs, int grid_dimension);

// The dimensions that occur in either diagram, ascending.
std::vector<int> diagram_dimensions(const PersistenceDiagram &a, const PersistenceDiagram &b);

} // namespace arbor::topology
