// grid_geometry.hpp - the LPS placement of a voxel grid, in the form the SDK's
// arbor_volume carries it, built from whatever affine map a file stores.
#pragma once

#include <arbor/volume.h>

#include <array>

namespace arbor::importer_vtk {

// Centre of voxel (i, j, k) = origin + D * (spacing[0]*i, spacing[1]*j,
// spacing[2]*k), LPS millimetres; D row-major, its columns unit vectors.
struct GridGeometry {
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0};
    std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1};

    void write_to(arbor_volume &out) const;
};

// Splits the map index -> LPS position p = matrix * (i, j, k) + translation
// (matrix row-major, its columns the grid steps) into spacing = column
// lengths and direction = unit columns.  A zero column keeps its axis
// direction and gets spacing 0, which the host's header check refuses with a
// message about the spacing.
GridGeometry geometry_from_affine(const std::array<double, 9> &matrix,
                                  const std::array<double, 3> &translation);

} // namespace arbor::importer_vtk
