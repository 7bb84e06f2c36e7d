// persistence_diagram_vtu.hpp - a persistence diagram as a VTK unstructured
// grid (.vtu) laid out as TTK's PersistenceDiagram filter outputs it, so that
// TTK's diagram filters in ParaView (distances, clustering, thresholds) and
// any VTK reader take it:
//   points       two per pair: (birth, birth, 0) and (birth, death, 0)
//   cells        a VTK_LINE per pair joining its two points, then one more
//                line, the diagonal, from point 0 to the point (b, b, 0) of
//                the largest birth b
//   point data   ttkVertexScalarField (int): the vertex id x + nx (y + ny z)
//                CriticalType (int): 0 minimum, 1 join saddle (1-saddle),
//                  2 split saddle (2-saddle; 1 on a single slice), 3 maximum
//                Coordinates (float x3): the vertex's position in mm (LPS)
//   cell data    PairIdentifier (int): the pair's index; -1 for the diagonal
//                PairType (int): the homology dimension (0; 2 for saddle -
//                  maximum pairs of a volume, 1 of a slice); -1 diagonal
//                Persistence (double): death - birth (the diagonal: twice the
//                  essential pair's, as TTK writes it)
//                Birth (double): the birth value (0 for the diagonal)
//                IsFinite (unsigned char): 0 for the essential pair (global
//                  minimum, global maximum) and the diagonal, else 1
// The essential pair comes first, as in TTK's output.  Written with VTK's
// XML writer (binary, zlib) to a temporary file that replaces `path` only
// once complete.
#pragma once

#include "core/volume.hpp"
#include "topology/persistence_pairs.hpp"

#include <filesystem>
#include <vector>

namespace arbor::io {

// Throws std::runtime_error naming the file when it cannot be written.
void write_persistence_diagram_vtu(const std::filesystem::path &path,
                                   const std::vector<topology::PersistencePair> &pairs, const Geometry &grid);

} // namespace arbor::io
