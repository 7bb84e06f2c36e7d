// persistence_pairs.hpp - the saddle-extremum pairs of a branch
// decomposition, in the text format of the TTK reference files
// (shared/reference/ttk): one pair a line,
//   type birth_vertex death_vertex birth_value death_value persistence bx by bz dx dy dz
// type 0 = (minimum, join saddle), 2 = (split saddle, maximum), -1 = (global
// minimum, global maximum); grid coordinates; sorted by persistence, then
// type, then birth and death vertex.
#pragma once

#include "branch_decomposition.hpp"

#include <cstdint>
#include <iosfwd>
#include <vector>

namespace arbor::topology {

struct PersistencePair {
    int type;
    uint32_t birth, death; // vertex ids
    double birth_value, death_value;
    double persistence() const { return death_value - birth_value; }
};

std::vector<PersistencePair> persistence_pairs(const ContourTree &tree, const BranchDecomposition &d,
                                               const FieldView &field);

// Writes the pairs with a header of '#' comment lines.  Integer voxel types
// print values as integers, floating point ones with round-trip precision.
void write_persistence_pairs(std::ostream &out, const std::vector<PersistencePair> &pairs,
                             const Geometry &grid, arbor_voxel_type type, const std::string &source);

} // namespace arbor::topology
