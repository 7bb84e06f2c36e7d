#include "critical_points.hpp"

#include "grid_neighbors.hpp"

#include <stdexcept>

namespace arbor::topology {

namespace {

template <class T> ExtremumCount count(const T *f, const GridNeighbors &grid)
{
    ExtremumCount c;
    const int64_t n = grid.size();
    for (int64_t v = 0; v < n; ++v) {
        bool lower = false, higher = false;
        const T x = f[v];
        grid.for_each(v, [&](int64_t u) {
            const bool below = f[u] < x || (f[u] == x && u < v);
            lower |= below;
            higher |= !below;
        });
        c.minima += !lower;
        c.maxima += !higher;
    }
    return c;
}

} // namespace

ExtremumCount count_extrema(arbor_voxel_type type, const void *values, int64_t nx, int64_t ny, int64_t nz)
{
    const GridNeighbors grid(nx, ny, nz);
    switch (type) {
    case ARBOR_VOXEL_U8: return count(static_cast<const uint8_t *>(values), grid);
    case ARBOR_VOXEL_I8: return count(static_cast<const int8_t *>(values), grid);
    case ARBOR_VOXEL_U16: return count(static_cast<const uint16_t *>(values), grid);
    case ARBOR_VOXEL_I16: return count(static_cast<const int16_t *>(values), grid);
    case ARBOR_VOXEL_U32: return count(static_cast<const uint32_t *>(values), grid);
    case ARBOR_VOXEL_I32: return count(static_cast<const int32_t *>(values), grid);
    case ARBOR_VOXEL_F32: return count(static_cast<const float *>(values), grid);
    case ARBOR_VOXEL_F64: return count(static_cast<const double *>(values), grid);
    default: throw std::invalid_argument("unknown voxel type");
    }
}

} // namespace arbor::topology
