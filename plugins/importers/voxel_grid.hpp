// voxel_grid.hpp - what an importer learns from a header: voxel type, dims,
// LPS geometry and the stored->physical value mapping, plus the conversions
// and checks every importer shares (filling the host's header record,
// comparing the host's volume with the file before writing into it).
#pragma once

#include <arbor/volume.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace arbor::importers {

struct VoxelGrid {
    arbor_voxel_type type = ARBOR_VOXEL_UNKNOWN;
    std::array<int64_t, 3> dims{1, 1, 1};
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0};
    std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1}; // row-major, columns = axes
};

struct ValueMapping {
    double scale = 1.0;
    double offset = 0.0;
    std::string unit;
};

// "103 x 94 x 161 u16"
std::string grid_text(const VoxelGrid &grid);

// Bytes of voxel data the grid needs; nullopt when that overflows 64 bits.
std::optional<uint64_t> voxel_bytes(const VoxelGrid &grid);

// Sets column `axis` of the direction matrix to the unit vector along `v`
// and returns the length of `v` (0 when v is zero or not finite, and then
// nothing is set).
double set_direction_column(VoxelGrid &grid, int axis, const std::array<double, 3> &v);

// Fills every header field but strides and voxels; the unit text is
// borrowed from `mapping`, which must outlive the host's use of `out`.
void write_volume_header(const VoxelGrid &grid, const ValueMapping &mapping, arbor_volume &out);

// Throws (ARBOR_ERROR_INVALID_ARGUMENT) unless the volume the host handed to
// read_voxels has the type and dims the file describes.
void require_matching_volume(const VoxelGrid &grid, const arbor_volume &volume,
                             std::string_view file_name);

} // namespace arbor::importers
