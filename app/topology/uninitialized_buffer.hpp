// uninitialized_buffer.hpp - a fixed-size array of trivially constructible
// elements for the topology core's one-element-per-voxel arrays.
//
// Nothing is written before use (std::vector would zero every page first),
// and large buffers come in huge pages (core/huge_pages.hpp).
#pragma once

#include "../core/huge_pages.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace arbor::topology {

template <class T>
class UninitializedBuffer {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);

public:
    UninitializedBuffer() = default;
    explicit UninitializedBuffer(std::size_t n, Pages pages = Pages::Huge) : size_(n)
    {
        if (n > static_cast<std::size_t>(-1) / sizeof(T))
            throw std::bad_array_new_length();
        if (n > 0)
            data_ = static_cast<T *>(allocate_large(n * sizeof(T), pages));
    }
    ~UninitializedBuffer() { release(); }
    UninitializedBuffer(UninitializedBuffer &&o) noexcept { swap(o); }
    UninitializedBuffer &operator=(UninitializedBuffer &&o) noexcept
    {
        if (this != &o) {
            release();
            swap(o);
        }
        return *this;
    }
    UninitializedBuffer(const UninitializedBuffer &) = delete;
    UninitializedBuffer &operator=(const UninitializedBuffer &) = delete;

    T &operator[](std::size_t i) { return data_[i]; }
    const T &operator[](std::size_t i) const { return data_[i]; }
    T *data() { return data_; }
    const T *data() const { return data_; }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

    // The first n * sizeof(U) bytes, already written as n U's by the caller,
    // as a buffer of its own; the rest goes back to the system.  A
    // per-vertex result made in place of per-vertex work space never holds
    // both.
    template <class U>
    UninitializedBuffer<U> shrink_to(std::size_t n) &&
    {
        static_assert(std::is_trivially_copyable_v<U>);
        const std::size_t bytes = size_ * sizeof(T), kept = n * sizeof(U);
        if (kept > bytes)
            throw std::length_error("UninitializedBuffer::shrink_to: larger than the buffer");
        UninitializedBuffer<U> out;
        if (bytes < kHugePageThreshold || kept < kHugePageThreshold) {
            // Not mapped, or too small to stay mapped: copied.
            out = UninitializedBuffer<U>(n, Pages::Small);
            if (kept > 0)
                std::memcpy(static_cast<void *>(out.data()), data_, kept);
            release();
            return out;
        }
        // Mapped: the pages past the kept bytes are unmapped.
        constexpr std::size_t kPage = 4096;
        const std::size_t tail = (kept + kPage - 1) / kPage * kPage;
        char *c = reinterpret_cast<char *>(data_);
        for (std::size_t at = tail; at < bytes; at += kPopulateBytes)
            munmap(c + at, std::min(bytes - at, kPopulateBytes));
        out.data_ = reinterpret_cast<U *>(data_);
        out.size_ = n;
        data_ = nullptr;
        size_ = 0;
        return out;
    }

    void release()
    {
        free_large(data_, size_ * sizeof(T));
        data_ = nullptr;
        size_ = 0;
    }

private:
    template <class>
    friend class UninitializedBuffer;

    void swap(UninitializedBuffer &o) noexcept
    {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
    }

    T *data_ = nullptr;
    std::size_t size_ = 0;
};

} // namespace arbor::topology
