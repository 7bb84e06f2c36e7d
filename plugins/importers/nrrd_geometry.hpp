// nrrd_geometry.hpp - the geometry fields of a NRRD header ("space", "space
// dimension", "space directions", "space origin", "spacings") turned into
// LPS spacing, direction cosines and origin.
#pragma once

#include "nrrd_fields.hpp"
#include "voxel_grid.hpp"

namespace arbor::importers {

// Sets grid.spacing, grid.direction and grid.origin for a header with
// `dimension` axes (2 or 3).  Directions are the normalised space-direction
// vectors and spacings their lengths; without space directions, "spacings"
// (default 1) along the LPS axes.  Throws ARBOR_ERROR_FORMAT for malformed
// fields and ARBOR_ERROR_UNSUPPORTED for non-spatial axes or time spaces.
void read_nrrd_geometry(const NrrdFields &fields, int dimension, VoxelGrid &grid);

} // namespace arbor::importers
