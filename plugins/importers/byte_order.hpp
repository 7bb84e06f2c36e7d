// byte_order.hpp - voxel byte order: which order a file uses relative to
// this machine, and swapping voxels in place in the host's buffer.
#pragma once

#include <bit>
#include <cstdint>

namespace arbor::importers {

// True when values stored in `file_order` must be swapped to be read here.
constexpr bool needs_swap(std::endian file_order)
{
    return file_order != std::endian::native;
}

// Reverses the bytes of each of `count` elements of `element_size` bytes
// (1, 2, 4 or 8; 1 leaves the data alone).
void swap_byte_order(void *data, uint64_t count, uint32_t element_size);

} // namespace arbor::importers
