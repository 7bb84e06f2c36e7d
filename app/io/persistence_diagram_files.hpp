// persistence_diagram_files.hpp - persistence diagrams in files.
//
// Read (plain or gzip, told apart by content):
//   - the pair text of `arbor pairs` and of TTK's reference files
//     (shared/reference/ttk/*.pairs.txt.gz): '#' comment lines, one of which
//     may carry "dims=nx ny nz" (the grid, for the dimension of saddle-maximum
//     pairs), then lines "type birth_vertex death_vertex birth_value
//     death_value ..." with type 0, 1, 2 or -1 (persistence_diagram.hpp);
//   - the CSV of `arbor pairs --format csv`: a header line naming the columns,
//     of which `dimension`, `birth` and `death` are needed and `essential`
//     (0/1) is read when present.
// Errors name the file and line: "pairs.txt:12: ...".
//
// Written: the CSV, one row per pair, columns
//   dimension,birth,death,persistence,essential,birth_vertex,death_vertex,bx,by,bz,dx,dy,dz
// (values as stored: integers for integer voxel types, 9 significant digits
// for floating point; coordinates are grid indices).
#pragma once

#include "core/volume.hpp"
#include "topology/persistence_diagram.hpp"
#include "topology/persistence_pairs.hpp"

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace arbor::io {

// Throws std::runtime_error naming the file (and line) when it cannot be
// read or is malformed.
topology::PersistenceDiagram read_persistence_diagram(const std::filesystem::path &path);

void write_pairs_csv(std::ostream &out, const std::vector<topology::PersistencePair> &pairs, const Geometry &grid,
                     arbor_voxel_type type);

} // namespace arbor::io
