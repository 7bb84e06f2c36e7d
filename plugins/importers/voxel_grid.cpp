// voxel_grid.cpp - see voxel_grid.hpp.
#include "voxel_grid.hpp"

#include <arbor/sdk/error.hpp>

#include <cmath>

namespace arbor::importers {

std::string grid_text(const VoxelGrid &grid)
{
    return std::to_string(grid.dims[0]) + " x " + std::to_string(grid.dims[1]) + " x " +
           std::to_string(grid.dims[2]) + " " + arbor_voxel_type_name(grid.type);
}

std::optional<uint64_t> voxel_bytes(const VoxelGrid &grid)
{
    uint64_t total = arbor_voxel_size(grid.type);
    for (int64_t d : grid.dims) {
        if (d <= 0)
            return std::nullopt;
        if (__builtin_mul_overflow(total, static_cast<uint64_t>(d), &total))
            return std::nullopt;
    }
    return total;
}

double set_direction_column(VoxelGrid &grid, int axis, const std::array<double, 3> &v)
{
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!std::isfinite(length) || length == 0.0)
        return 0.0;
    for (int row = 0; row < 3; ++row)
        grid.direction[3 * row + axis] = v[row] / length;
    return length;
}

void write_volume_header(const VoxelGrid &grid, const ValueMapping &mapping, arbor_volume &out)
{
    out.voxel_type = grid.type;
    for (int a = 0; a < 3; ++a) {
        out.dims[a] = grid.dims[a];
        out.spacing[a] = grid.spacing[a];
        out.origin[a] = grid.origin[a];
    }
    for (int e = 0; e < 9; ++e)
        out.direction[e] = grid.direction[e];
    out.value_scale = mapping.scale;
    out.value_offset = mapping.offset;
    out.value_unit = mapping.unit.c_str();
}

void require_matching_volume(const VoxelGrid &grid, const arbor_volume &volume,
                             std::string_view file_name)
{
    const bool same = volume.voxel_type == grid.type && volume.dims[0] == grid.dims[0] &&
                      volume.dims[1] == grid.dims[1] && volume.dims[2] == grid.dims[2];
    if (same)
        return;
    VoxelGrid given;
    given.type = volume.voxel_type;
    for (int a = 0; a < 3; ++a)
        given.dims[a] = volume.dims[a];
    sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the volume given to read " + std::string(file_name) +
                                                " is " + grid_text(given) +
                                                ", but the file holds " + grid_text(grid));
}

} // namespace arbor::importers
