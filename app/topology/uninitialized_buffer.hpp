// uninitialized_buffer.hpp - a fixed-size array of trivially constructible
// elements for the topology core's one-element-per-voxel arrays.
//
// Nothing is written before use (std::vector would zero every page first),
// and large buffers come in huge pages (core/huge_pages.hpp).
#pragma once

#include "../core/huge_pages.hpp"

#include <cstddef>
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

    void release()
    {
        free_large(data_, size_ * sizeof(T));
        data_ = nullptr;
        size_ = 0;
    }

private:
    void swap(UninitializedBuffer &o) noexcept
    {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
    }

    T *data_ = nullptr;
    std::size_t size_ = 0;
};

} // namespace arbor::topology
