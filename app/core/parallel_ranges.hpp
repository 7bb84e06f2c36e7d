// parallel_ranges.hpp - a loop over [0, n) split into contiguous ranges, one
// per core, for the per-voxel passes of the core (labelling, measuring).
//
// Plain joined threads rather than a task pool: the join is what
// ThreadSanitizer sees as the order between the workers' writes and the
// caller's reads (under oneTBB's pool it reports races that are not there),
// and passes of tens of millions of voxels do not need work stealing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace arbor {

// How many ranges for_ranges makes: one per core, each of at least
// `min_per_part` elements, and at least one.
inline std::size_t range_parts(std::size_t n, std::size_t min_per_part)
{
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    return std::clamp<std::size_t>(n / std::max<std::size_t>(min_per_part, 1), 1, cores);
}

// Calls body(begin, end, part) for the range_parts(n, min_per_part)
// contiguous ranges covering [0, n), the first on the calling thread, and
// returns their number.  `body` must not throw.  Where no thread can be had,
// the calling thread does the rest.
template <class Body>
std::size_t for_ranges(std::size_t n, std::size_t min_per_part, const Body &body)
{
    const std::size_t parts = range_parts(n, min_per_part);
    const auto bound = [&](std::size_t p) { return n / parts * p + std::min(p, n % parts); };
    std::vector<std::jthread> helpers;
    std::size_t started = 1;
    try {
        for (; started < parts; ++started)
            helpers.emplace_back([&body, &bound, started] { body(bound(started), bound(started + 1), started); });
    } catch (...) {
        // No thread to be had: the parts not started run here.
    }
    body(bound(0), bound(1), 0);
    for (std::size_t p = started; p < parts; ++p)
        body(bound(p), bound(p + 1), p);
    return parts;
}

} // namespace arbor
