// nrrd_writer.hpp - write a Volume as a NRRD file (attached header), the
// format Arbor writes volumes and label maps in.  Geometry goes into `space:
// left-posterior-superior`, `space directions` and `space origin`, so 3D
// Slicer and ITK place the volume correctly; the value mapping goes into
// key/value pairs that Arbor's NRRD importer reads back.
#pragma once

#include "core/volume.hpp"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace arbor::io {

struct NrrdWriteOptions {
    bool gzip = true;
    int gzip_level = 6;
    std::string content;                                       // "content:" field
    std::vector<std::pair<std::string, std::string>> key_values; // extra "key:=value" lines
};

// Throws std::runtime_error naming the file on failure; an existing file is
// only replaced once the new one is complete.
void write_nrrd(const Volume &volume, const std::filesystem::path &path,
                const NrrdWriteOptions &options = {});

// NRRD type name of a voxel type ("uint8", "int16", "float"...).
const char *nrrd_type_name(arbor_voxel_type type);

} // namespace arbor::io
