// volume_header.hpp - the one place that decides whether a volume header is
// acceptable before any voxel memory is allocated.
//
// Every importer's header passes through check_volume_header, so malformed or
// hostile headers (zero or negative dims, products that overflow, a claim of
// 100000^3 voxels, NaN spacing) are refused with a message instead of
// reaching the allocator.
#pragma once

#include <arbor/volume.h>

#include <cstdint>
#include <string>

namespace arbor {

// Voxel indices are stored in 32 bits by the topology core.
inline constexpr int64_t kMaxVoxelCount = 4294967295LL - 1;

// Largest voxel buffer the host allocates: half the physical memory, or the
// value of the environment variable ARBOR_MAX_VOLUME_BYTES when set.
uint64_t default_max_volume_bytes();

// "" when the header is acceptable, otherwise a sentence saying what is wrong.
std::string check_volume_header(const arbor_volume &header, uint64_t max_bytes);

// "512 x 512 x 300", for messages.
std::string dims_text(const int64_t dims[3]);

// "1.5 GB", "312 kB"...
std::string format_bytes(uint64_t bytes);

} // namespace arbor
