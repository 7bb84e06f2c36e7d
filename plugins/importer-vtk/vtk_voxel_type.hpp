// vtk_voxel_type.hpp - which VTK scalar types become which SDK voxel types.
#pragma once

#include <arbor/volume.h>

#include <string>

namespace arbor::importer_vtk {

// The SDK voxel type holding values of VTK type `vtk_type` (VTK_UNSIGNED_CHAR,
// VTK_FLOAT...) unchanged, or ARBOR_VOXEL_UNKNOWN for types with no such
// counterpart (64-bit integers, bits, strings).
arbor_voxel_type voxel_type_of(int vtk_type);

// "unsigned short", "long long", "bit"... for messages.
std::string vtk_type_name(int vtk_type);

} // namespace arbor::importer_vtk
