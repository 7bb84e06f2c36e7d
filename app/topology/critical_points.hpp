// critical_points.hpp - how many minima and maxima a field has, without its
// contour tree: a vertex of the Freudenthal triangulation is a minimum when
// every neighbour is higher (simulation of simplicity: value, then id), a
// maximum when every neighbour is lower.  These are exactly the contour
// tree's extrema, so minima + maxima - 1 is its branch count, found in one
// pass: what choosing a denoising strength needs to try many strengths.
#pragma once

#include <arbor/volume.h>

#include <cstdint>

namespace arbor::topology {

struct ExtremumCount {
    uint64_t minima = 0, maxima = 0;
    uint64_t branches() const { return minima + maxima > 0 ? minima + maxima - 1 : 0; }
};

ExtremumCount count_extrema(arbor_voxel_type type, const void *values, int64_t nx, int64_t ny, int64_t nz);

} // namespace arbor::topology
