// unset_vector.hpp - a std::vector whose resize() leaves new elements of a
// trivial type unwritten, for the per-voxel copies a ray caster fills
// completely right after sizing them: std::vector would write every byte
// twice (zeros, then the values), and on a 512 x 512 x 300 CT the zeros
// alone cost about as much as computing the normals.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace arbor::raycast {

template <class T, class Base = std::allocator<T>>
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
