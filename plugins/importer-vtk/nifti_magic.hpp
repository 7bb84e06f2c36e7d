// nifti_magic.hpp - recognising a NIfTI-1 or NIfTI-2 header by its magic
// string, in plain or gzip-compressed bytes.
#pragma once

#include <cstdint>

namespace arbor::importer_vtk {

enum class NiftiMagic {
    none,
    single_file, // "n+1" / "n+2": header and voxels in one .nii
    pair_header, // "ni1" / "ni2": a .hdr whose voxels lie in a .img
};

// Looks at the first `size` bytes of a file (gzip streams are inflated as far
// as those bytes go).  Cheap enough for probing.
NiftiMagic find_nifti_magic(const uint8_t *head, uint64_t size);

} // namespace arbor::importer_vtk
