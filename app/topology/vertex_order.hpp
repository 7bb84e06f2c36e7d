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
#include <vector>

namespace arbor::topology {

// Progress callback: fraction in [0, 1]; may throw to cancel.
using ProgressFn = std::function<void(double)>;

// The vertex ids of n vertices whose values are `values` of voxel type
// `type`, lowest first.
UninitializedBuffer<uint32_t> sort_vertices(arbor_voxel_type type, const void *values, uint32_t n,
                                            const ProgressFn &progress = {});

// Whether `type` is ordered by counting (8- and 16-bit values), which is
// what lets the order be made a range at a time (fill_order_range).
bool orders_by_counting(arbor_voxel_type type);

// For a type ordered by counting: entry k is how many vertices have a value
// below the k-th possible one (2^8 or 2^16 buckets, and n last), so the
// vertices of value k are at ranks [starts[k], starts[k + 1]) of the order.
std::vector<uint32_t> count_value_starts(arbor_voxel_type type, const void *values, uint32_t n);

// The vertices of ranks [lo, hi) of the order, by one scan of the values:
// rank r goes to out[r - lo], or to out[hi - 1 - r] when `reversed` (the
// order walked downwards).  `starts` is count_value_starts of the same
// values.  Memory: hi - lo words, where sort_vertices needs n.
void fill_order_range(arbor_voxel_type type, const void *values, uint32_t n, const std::vector<uint32_t> &starts,
                      uint32_t lo, uint32_t hi, bool reversed, uint32_t *out);

} // namespace arbor::topology
