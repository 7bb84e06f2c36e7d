// uninitialized_buffer.hpp - a fixed-size array of trivially constructible
// elements for the topology core's one-element-per-voxel arrays.
//
// Two things matter for arrays of hundreds of megabytes that the sweeps read
// at random: nothing should be written before use (std::vector would zero
// every page first), and the memory should come in huge pages, which cuts the
// page faults on first touch and the TLB misses of random access by a factor
// of 512.  Large buffers are therefore mapped directly and advised as huge
// pages (Linux transparent huge pages, "madvise" mode); small ones use new[].
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include <sys/mman.h>

namespace arbor::topology {

template <class T>
class UninitializedBuffer {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);

public:
    UninitializedBuffer() = default;
    explicit UninitializedBuffer(std::size_t n) : size_(n)
    {
        const std::size_t bytes = n * sizeof(T);
        if (bytes >= kMapThreshold) {
            void *p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            if (p == MAP_FAILED)
                throw std::bad_alloc();
            madvise(p, bytes, MADV_HUGEPAGE);
            data_ = static_cast<T *>(p);
            mapped_ = true;
        } else if (n > 0) {
            data_ = new T[n];
        }
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
        if (mapped_)
            munmap(data_, size_ * sizeof(T));
        else
            delete[] data_;
        data_ = nullptr;
        size_ = 0;
        mapped_ = false;
    }

private:
    static constexpr std::size_t kMapThreshold = std::size_t{4} << 20;

    void swap(UninitializedBuffer &o) noexcept
    {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
        std::swap(mapped_, o.mapped_);
    }

    T *data_ = nullptr;
    std::size_t size_ = 0;
    bool mapped_ = false;
};

} // namespace arbor::topology
