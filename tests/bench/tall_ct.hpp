// tall_ct.hpp - a chest CT's size from real scans, written once as NRRD
// (the renderer benchmarks' large inputs): the shared CT head DICOM
// (512 x 512 x 108) with `factor` times as many slices, and the shared
// LIDC chest CT (256 x 256 x 133) with twice the rows, columns and slices
// (511 x 511 x 265, the size of a clinical chest CT); linear between the
// voxels, so each keeps its scan's own content.
#pragma once

#include <array>
#include <filesystem>

namespace arbor::bench {

// The volume at `in` with (n - 1) * factor + 1 voxels along each axis,
// linear in between, at `out`, made unless it is there already.  8- and
// 16-bit unsigned voxels.
std::filesystem::path upsampled(const std::filesystem::path &in, const std::array<int, 3> &factor,
                                const std::filesystem::path &out);

// The resampled CT head at `out`, from the DICOM series at `dicom`.
inline std::filesystem::path tall_ct(const std::filesystem::path &dicom, int factor, const std::filesystem::path &out)
{
    return upsampled(dicom, {1, 1, factor}, out);
}

} // namespace arbor::bench
