// huge_pages.hpp - memory for large arrays: voxels and the topology core's
// per-vertex, per-node and per-arc arrays.
//
// Arrays of hundreds of megabytes that are read at random should come in huge
// pages: one page fault and one TLB entry per 2 MiB instead of per 4 KiB.
// Large blocks are therefore mapped directly and advised as transparent huge
// pages (Linux, "madvise" mode); small ones use operator new.  HugeVector is
// a std::vector with this allocation, for the per-node and per-arc arrays of
// the contour tree and its branch decomposition; StreamedVector the same in
// small pages, for per-voxel arrays read in order (the label map).
#pragma once

#include <algorithm>
#include <cstddef>
#include <new>
#include <thread>
#include <vector>

#include <sys/mman.h>

namespace arbor {

// Blocks of at least this many bytes are mapped directly and advised as huge
// pages.  Page faults are expensive on virtual machines: even a 1 MiB scratch
// array is faster this way (radix sort of 64^3 floats: 12 ms -> 4.5 ms).
inline constexpr std::size_t kHugePageThreshold = std::size_t{256} << 10;

// Mappings are whole huge pages: Linux aligns anonymous mappings whose length
// is a multiple of 2 MiB to a 2 MiB boundary, so every page can be huge.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
// How much one call populates (MADV_POPULATE_WRITE) or unmaps: a few huge
// pages, so that no call holds the memory-map lock for long.
inline constexpr std::size_t kPopulateBytes = std::size_t{4} << 20;
inline std::size_t mapped_bytes(std::size_t bytes) { return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes; }

// Blocks of at least this many bytes are populated by several threads.
inline constexpr std::size_t kParallelPopulateBytes = std::size_t{64} << 20;

// Faults a fresh mapping in.  Populated a piece at a time: one call holds
// the process' memory-map lock while it faults (and compacts) the whole
// range in, and every other thread's page fault waits behind it - a
// workstation's UI thread stalled 400 ms on a 1 MiB allocation while a
// volume was populated.  Large blocks are split between threads: on a
// virtual machine the first touch of a huge page costs a fault of the host
// for each of its small pages as well as the zeroing, 2-3 s a gigabyte, and
// those faults run in parallel (4 GB: 2.0-3.0 s on one thread, 0.9-1.3 s
// on two).  Small pages would populate 3-4 times faster there, but the
// random reads of the sweeps then miss the TLB: the tree is no faster.
inline void populate_pages(char *c, std::size_t bytes)
{
    const auto populate = [c](std::size_t from, std::size_t to) {
        for (std::size_t at = from; at < to; at += kPopulateBytes)
            madvise(c + at, std::min(to - at, kPopulateBytes), MADV_POPULATE_WRITE);
    };
    const std::size_t threads =
        bytes < kParallelPopulateBytes ? 1 : std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 4);
    if (threads == 1) {
        populate(0, bytes);
        return;
    }
    // Whole pieces per thread; the calling thread takes the first share.
    const std::size_t pieces = (bytes + kPopulateBytes - 1) / kPopulateBytes;
    const auto bound = [&](std::size_t t) { return std::min(bytes, pieces * t / threads * kPopulateBytes); };
    std::vector<std::thread> helpers;
    try {
        for (std::size_t t = 1; t < threads; ++t)
            helpers.emplace_back(populate, bound(t), bound(t + 1));
    } catch (...) {
        // No thread to be had: the rest is faulted in on first use.
    }
    populate(0, bound(1));
    for (std::thread &h : helpers)
        h.join();
}

// Which pages a large block gets.  Huge pages serve arrays read at random
// (the sweeps' component words: one TLB entry per 2 MiB).  Arrays that are
// streamed (volumes, the vertex order, the merge state in rank order, the
// segmentation) take small pages: on a
// virtual machine a huge page comes from memory the host has not backed yet
// and costs 2-3 s a gigabyte to fault in, small pages come mostly from
// memory freed a moment ago, 0.5-0.7 s a gigabyte.
enum class Pages { Huge, Small };

inline void *allocate_large(std::size_t bytes, Pages pages = Pages::Huge)
{
    if (bytes < kHugePageThreshold)
        return ::operator new(bytes);
    void *p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED)
        throw std::bad_alloc();
    madvise(p, bytes, pages == Pages::Huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
    populate_pages(static_cast<char *>(p), bytes);
    return p;
}

inline void free_large(void *p, std::size_t bytes) noexcept
{
    if (!p)
        return;
    if (bytes < kHugePageThreshold) {
        ::operator delete(p);
        return;
    }
    // Unmapped a piece at a time, for the same reason as it is populated.
    char *c = static_cast<char *>(p);
    for (std::size_t at = 0; at < bytes; at += kPopulateBytes)
        munmap(c + at, bytes - at < kPopulateBytes ? bytes - at : kPopulateBytes);
}

// Large blocks mapped directly and faulted in by populate_pages, in huge or
// small pages (`P`).  On a virtual machine this is what makes a large array
// cheap: 315 MB zeroed by std::vector (one fault per page touched) took
// 1.1 s, faulted in by MADV_POPULATE_WRITE 0.07 s.
template <class T, Pages P = Pages::Huge>
struct LargeAllocator {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = LargeAllocator<U, P>;
    };

    LargeAllocator() = default;
    template <class U>
    LargeAllocator(const LargeAllocator<U, P> &) noexcept
    {
    }

    T *allocate(std::size_t n)
    {
        if (n > static_cast<std::size_t>(-1) / sizeof(T))
            throw std::bad_array_new_length();
        return static_cast<T *>(allocate_large(n * sizeof(T), P));
    }
    void deallocate(T *p, std::size_t n) noexcept { free_large(p, n * sizeof(T)); }

    template <class U>
    bool operator==(const LargeAllocator<U, P> &) const noexcept
    {
        return true;
    }
};

// Per-node and per-arc arrays of the topology core, read at random.
template <class T>
using HugeVector = std::vector<T, LargeAllocator<T, Pages::Huge>>;

// Per-voxel arrays that are streamed (the label map).
template <class T>
using StreamedVector = std::vector<T, LargeAllocator<T, Pages::Small>>;

} // namespace arbor
