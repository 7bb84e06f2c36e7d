// nifti_header_check.hpp - the checks a NIfTI header must pass before
// vtkNIFTIImageReader sees it.
//
// VTK 9.1's reader trusts its input: an unknown datatype code makes it read
// past its own type table and crash, and dimensions beyond the third feed
// its size arithmetic unchecked.  So the fields it relies on are read here,
// independently, and anything malformed or unsupported is refused with a
// message first.
#pragma once

#include <cstdint>
#include <string>

namespace arbor::importer_vtk {

struct NiftiEssentials {
    int version = 1;          // 1 or 2
    bool single_file = true;  // "n+": voxels follow the header; "ni": in a .img
    int64_t dim[8] = {};
    int datatype = 0;
    double vox_offset = 0.0;
};

// Reads the header of `path` (plain or gzip) and throws ARBOR_ERROR_FORMAT
// (damaged fields, an uncompressed file too short for its voxels) or
// ARBOR_ERROR_UNSUPPORTED (Analyze 7.5 without NIfTI magic, complex, RGB,
// 64-bit or vector data) naming `name`.
NiftiEssentials check_nifti_header(const std::string &path, const std::string &name,
                                   uint64_t file_size);

} // namespace arbor::importer_vtk
