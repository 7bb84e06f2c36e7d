#include "vertex_order.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <stdexcept>
#include <vector>

namespace arbor::topology {

namespace {

// Order-preserving unsigned keys.
inline uint32_t key32(uint32_t x) { return x; }
inline uint32_t key32(int32_t x) { return static_cast<uint32_t>(x) ^ 0x80000000u; }
inline uint32_t key32(float x)
{
    if (x == 0.0f)
        x = 0.0f; // -0.0 and +0.0 are equal values
    const uint32_t b = std::bit_cast<uint32_t>(x);
    return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
inline uint64_t key64(double x)
{
    if (x == 0.0)
        x = 0.0;
    const uint64_t b = std::bit_cast<uint64_t>(x);
    return (b & 0x8000000000000000ull) ? ~b : (b | 0x8000000000000000ull);
}

template <class T>
inline uint32_t small_key(T x)
{
    if constexpr (std::is_signed_v<T>)
        return static_cast<uint32_t>(static_cast<int32_t>(x) - static_cast<int32_t>(std::numeric_limits<T>::min()));
    else
        return static_cast<uint32_t>(x);
}

// Where each value's run starts in the ascending order (value_starts[k]
// for small_key k), one histogram and its prefix sums.
template <class T>
std::vector<uint32_t> value_starts(const T *v, uint32_t n)
{
    constexpr std::size_t buckets = std::size_t{1} << (8 * sizeof(T));
    std::vector<uint32_t> start(buckets + 1, 0);
    for (uint32_t i = 0; i < n; ++i)
        ++start[small_key(v[i]) + 1];
    for (std::size_t b = 0; b < buckets; ++b)
        start[b + 1] += start[b];
    return start;
}

// Counting sort for 8- and 16-bit values: one histogram, one scatter.
template <class T>
void counting_sort(const T *v, uint32_t n, uint32_t *order, const ProgressFn &progress)
{
    std::vector<uint32_t> start = value_starts(v, n);
    if (progress)
        progress(0.4);
    for (uint32_t i = 0; i < n; ++i)
        order[start[small_key(v[i])]++] = i;
}

// LSD radix sort of 32-bit keys with three 11-bit digits: 2048 buckets keep
// each scatter's write heads in L1 and the TLB, which beats two passes over
// 65536 buckets by about 2x at every size.  Key and vertex travel packed in
// one 64-bit word (key high), so each pass streams one array.
template <class T>
void radix_sort32(const T *v, uint32_t n, uint32_t *order, const ProgressFn &progress)
{
    constexpr int kBits = 11;
    constexpr std::size_t kBuckets = std::size_t{1} << kBits;
    constexpr uint32_t kMask = kBuckets - 1;
    std::vector<uint32_t> count(3 * kBuckets, 0);
    uint32_t *c0 = count.data(), *c1 = c0 + kBuckets, *c2 = c1 + kBuckets;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t k = key32(v[i]);
        ++c0[k & kMask];
        ++c1[(k >> kBits) & kMask];
        ++c2[k >> (2 * kBits)];
    }
    for (uint32_t *c : {c0, c1, c2}) {
        uint32_t sum = 0;
        for (std::size_t b = 0; b < kBuckets; ++b)
            sum += std::exchange(c[b], sum);
    }
    UninitializedBuffer<uint64_t> a(n), b(n);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t k = key32(v[i]);
        a[c0[k & kMask]++] = (uint64_t{k} << 32) | i;
    }
    if (progress)
        progress(0.4);
    for (uint32_t p = 0; p < n; ++p)
        b[c1[(a[p] >> (32 + kBits)) & kMask]++] = a[p];
    if (progress)
        progress(0.7);
    for (uint32_t p = 0; p < n; ++p)
        order[c2[b[p] >> (32 + 2 * kBits)]++] = static_cast<uint32_t>(b[p]);
}

// LSD radix sort with 16-bit digits of 64-bit keys: four stable passes.
void radix_sort64(const double *v, uint32_t n, uint32_t *order, const ProgressFn &progress)
{
    constexpr std::size_t buckets = 1 << 16;
    std::vector<std::vector<uint32_t>> count(4, std::vector<uint32_t>(buckets + 1, 0));
    for (uint32_t i = 0; i < n; ++i) {
        const uint64_t k = key64(v[i]);
        for (int d = 0; d < 4; ++d)
            ++count[d][((k >> (16 * d)) & 0xffff) + 1];
    }
    for (int d = 0; d < 4; ++d)
        for (std::size_t b = 0; b < buckets; ++b)
            count[d][b + 1] += count[d][b];
    UninitializedBuffer<uint64_t> key_a(n), key_b(n);
    UninitializedBuffer<uint32_t> idx_a(n), idx_b(n);
    for (uint32_t i = 0; i < n; ++i) {
        key_a[i] = key64(v[i]);
        idx_a[i] = i;
    }
    for (int d = 0; d < 4; ++d) {
        std::vector<uint32_t> &c = count[d];
        for (uint32_t p = 0; p < n; ++p) {
            const uint32_t at = c[(key_a[p] >> (16 * d)) & 0xffff]++;
            key_b[at] = key_a[p];
            idx_b[at] = idx_a[p];
        }
        std::swap(key_a, key_b);
        std::swap(idx_a, idx_b);
        if (progress)
            progress(0.2 * (d + 1));
    }
    std::memcpy(order, idx_a.data(), sizeof(uint32_t) * n);
}

// The scatter of counting_sort restricted to the values whose ranks meet
// [lo, hi): a cursor per such value, and a write only for ranks in range.
template <class T>
void fill_range(const T *v, uint32_t n, const std::vector<uint32_t> &starts, uint32_t lo, uint32_t hi, bool reversed,
                uint32_t *out)
{
    if (starts.size() != (std::size_t{1} << (8 * sizeof(T))) + 1)
        throw std::invalid_argument("fill_order_range: counts of another voxel type");
    if (lo >= hi)
        return;
    // The values holding ranks lo and hi - 1: the last k with starts[k] <= r.
    const auto value_of = [&](uint32_t r) {
        return static_cast<uint32_t>(std::upper_bound(starts.begin(), starts.end(), r) - starts.begin() - 1);
    };
    const uint32_t first = value_of(lo), span = value_of(hi - 1) - first;
    std::vector<uint32_t> cursor(starts.begin() + first, starts.begin() + first + span + 1);
    uint32_t *c = cursor.data();
    uint32_t left = hi - lo;
    for (uint32_t i = 0; i < n && left > 0; ++i) {
        const uint32_t k = small_key(v[i]) - first; // wraps for values below: out of range
        if (k > span)
            continue;
        const uint32_t r = c[k]++;
        if (r >= lo && r < hi) {
            out[reversed ? hi - 1 - r : r - lo] = i;
            --left;
        }
    }
}

} // namespace

bool orders_by_counting(arbor_voxel_type type)
{
    return type == ARBOR_VOXEL_U8 || type == ARBOR_VOXEL_I8 || type == ARBOR_VOXEL_U16 || type == ARBOR_VOXEL_I16;
}

std::vector<uint32_t> count_value_starts(arbor_voxel_type type, const void *values, uint32_t n)
{
    switch (type) {
    case ARBOR_VOXEL_U8: return value_starts(static_cast<const uint8_t *>(values), n);
    case ARBOR_VOXEL_I8: return value_starts(static_cast<const int8_t *>(values), n);
    case ARBOR_VOXEL_U16: return value_starts(static_cast<const uint16_t *>(values), n);
    case ARBOR_VOXEL_I16: return value_starts(static_cast<const int16_t *>(values), n);
    default: throw std::invalid_argument("only 8- and 16-bit values are ordered by counting");
    }
}

void fill_order_range(arbor_voxel_type type, const void *values, uint32_t n, const std::vector<uint32_t> &starts,
                      uint32_t lo, uint32_t hi, bool reversed, uint32_t *out)
{
    if (hi > n || lo > hi || starts.empty() || starts.back() != n)
        throw std::invalid_argument("fill_order_range: ranks out of range or counts of other values");
    switch (type) {
    case ARBOR_VOXEL_U8: fill_range(static_cast<const uint8_t *>(values), n, starts, lo, hi, reversed, out); break;
    case ARBOR_VOXEL_I8: fill_range(static_cast<const int8_t *>(values), n, starts, lo, hi, reversed, out); break;
    case ARBOR_VOXEL_U16: fill_range(static_cast<const uint16_t *>(values), n, starts, lo, hi, reversed, out); break;
    case ARBOR_VOXEL_I16: fill_range(static_cast<const int16_t *>(values), n, starts, lo, hi, reversed, out); break;
    default: throw std::invalid_argument("only 8- and 16-bit values are ordered by counting");
    }
}

UninitializedBuffer<uint32_t> sort_vertices(arbor_voxel_type type, const void *values, uint32_t n,
                                            const ProgressFn &progress)
{
    UninitializedBuffer<uint32_t> order(n, Pages::Small); // streamed
    switch (type) {
    case ARBOR_VOXEL_U8: counting_sort(static_cast<const uint8_t *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_I8: counting_sort(static_cast<const int8_t *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_U16: counting_sort(static_cast<const uint16_t *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_I16: counting_sort(static_cast<const int16_t *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_U32: radix_sort32(static_cast<const uint32_t *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_I32: radix_sort32(static_cast<const int32_t *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_F32: radix_sort32(static_cast<const float *>(values), n, order.data(), progress); break;
    case ARBOR_VOXEL_F64: radix_sort64(static_cast<const double *>(values), n, order.data(), progress); break;
    default: throw std::invalid_argument("cannot order vertices of unknown voxel type");
    }
    if (progress)
        progress(1.0);
    return order;
}

} // namespace arbor::topology
