// volume_checksum.hpp - a content checksum of a volume, so a report can say
// which data it was computed on whatever the file was called or how it was
// stored (a DICOM folder and its NRRD copy have the same voxels): XXH3-128
// over the voxel type, the grid (dims, spacing, origin, directions), the
// stored-to-physical mapping and the voxel bytes, as "xxh3-128:<32 hex>".
#pragma once

#include "core/volume.hpp"

#include <string>

namespace arbor::pipeline {

std::string volume_checksum(const Volume &volume);

} // namespace arbor::pipeline
