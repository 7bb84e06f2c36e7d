// nifti_geometry.hpp - the placement and value mapping of a NIfTI image in
// the SDK's conventions: LPS millimetres for voxels in file order.
#pragma once

#include "grid_geometry.hpp"

#include <array>
#include <string>

namespace arbor::importer_vtk {

// The spatial fields of a NIfTI-1/-2 header, as stored.
struct NiftiSpace {
    int qform_code = 0;
    int sform_code = 0;
    std::array<double, 8> pixdim{};            // pixdim[0] is qfac
    std::array<double, 3> quatern{};           // b, c, d
    std::array<double, 3> qoffset{};           // x, y, z
    std::array<std::array<double, 4>, 3> srow{}; // srow_x, srow_y, srow_z
    int xyzt_units = 0;
};

struct NiftiPlacement {
    GridGeometry geometry;
    const char *source = "pixdim"; // "sform", "qform" or "pixdim": which field placed it
};

// Geometry of voxel (i, j, k) in the file's own storage order: the sform when
// sform_code > 0, else the qform when qform_code > 0, else pixdim alone (each
// skipped when it is degenerate).  NIfTI world space is RAS; the x and y rows
// are negated for LPS.  Lengths in metres or microns are converted to mm.
NiftiPlacement place_nifti(const NiftiSpace &space);

// value_scale / value_offset from scl_slope / scl_inter: a slope of 0 or a
// non-finite slope means "no scaling" (NIfTI-1 standard).
struct NiftiValueMapping {
    double scale = 1.0;
    double offset = 0.0;
};
NiftiValueMapping nifti_value_mapping(double scl_slope, double scl_inter);

} // namespace arbor::importer_vtk
