// vertex_order.hpp - the total order of the grid's vertices by simulation of
// simplicity: vertex a is lower than b iff (f(a), a) < (f(b), b).  Equal
// values are never equal in this order, ties go to the lower vertex id
// (TTK's convention), so every vertex has a unique rank.
//
// 8- and 16-bit data are sorted by counting in O(n); 32- and 64-bit data by a
// stable least-significant-digit radix sort on order-preserving integer keys.
// Both are stable over vertex ids, which is exactly the tie rule.  -0.0 sorts
// as +0.0 (they compare equal as values).  NaN must be refused before.
#pragma once

#include "uninitialized_buffer.hpp"

#include <arbor/volume.h>

#include <cstdint>
#include <functional>

namespace arbor::topology {

// Progress callback: fraction in [0, 1]; may throw to cancel.
using ProgressFn = std::function<void(double)>;

// The vertex ids of n vertices whose values are `values` of voxel type
// `type`, lowest first.
UninitializedBuffer<uint32_t> sort_vertices(arbor_voxel_type type, const void *values, uint32_t n,
                                            const ProgressFn &progress = {});

} // namespace arbor::topology
