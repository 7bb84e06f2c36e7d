// unset_vector.hpp - a std::vector whose resize() leaves new elements of a
// trivial type unwritten, for the per-voxel copies a ray caster fills
// completely right after sizing them: std::vector would write every byte
// twice (zeros, then the values), and on a 512 x 512 x 300 CT the zeros
// alone cost about as much as computing the normals.  Large ones are mapped
// directly and faulted in with MADV_POPULATE_WRITE: on a virtual machine a
// page fault per 4 KiB touched is dear (315 MB: 1.1 s one page at a time,
// 0.07 s populated).
#pragma once

#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace arbor::raycast {

// Blocks of 256 KiB or more come from their own mapping, populated a few
// megabytes per call (a call holds the process' memory-map lock); smaller
// ones from operator new.  A kernel without MADV_POPULATE_WRITE (before
// Linux 5.14) leaves the pages to be faulted in on first use.
template <class T>
struct PopulatedAllocator {
    using value_type = T;
    static constexpr std::size_t kMapped = std::size_t{256} << 10;
    static constexpr std::size_t kPiece = std::size_t{4} << 20;

    PopulatedAllocator() = default;
    template <class U>
    PopulatedAllocator(const PopulatedAllocator<U> &) noexcept
    {
    }

    T *allocate(std::size_t n)
    {
        if (n > static_cast<std::size_t>(-1) / sizeof(T))
            throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kMapped)
            return static_cast<T *>(::operator new(bytes));
        void *p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED)
            throw std::bad_alloc();
        char *c = static_cast<char *>(p);
        for (std::size_t at = 0; at < bytes; at += kPiece)
            madvise(c + at, std::min(bytes - at, kPiece), MADV_POPULATE_WRITE);
        return static_cast<T *>(p);
    }
    void deallocate(T *p, std::size_t n) noexcept
    {
        if (n * sizeof(T) < kMapped)
            ::operator delete(p);
        else
            munmap(p, n * sizeof(T));
    }

    template <class U>
    bool operator==(const PopulatedAllocator<U> &) const noexcept
    {
        return true;
    }
};

template <class T, class Base = PopulatedAllocator<T>>
class DefaultInitAllocator : public Base {
    using Traits = std::allocator_traits<Base>;

public:
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U, typename Traits::template rebind_alloc<U>>;
    };
    using Base::Base;

    // Value-initialisation (resize(n), vector(n)) becomes default-
    // initialisation: nothing is written for a trivial type.
    template <class U>
    void construct(U *p) noexcept(std::is_nothrow_default_constructible_v<U>)
    {
        ::new (static_cast<void *>(p)) U;
    }
    template <class U, class... Args>
    void construct(U *p, Args &&...args)
    {
        Traits::construct(static_cast<Base &>(*this), p, std::forward<Args>(args)...);
    }
};

template <class T>
using UnsetVector = std::vector<T, DefaultInitAllocator<T>>;

} // namespace arbor::raycast
