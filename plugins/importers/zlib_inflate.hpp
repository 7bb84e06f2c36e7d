// zlib_inflate.hpp - decompresses gzip or zlib voxel data straight into the
// host's buffer, with progress and cancellation, never holding more than a
// small input buffer of its own.
#pragma once

#include "data_file.hpp"

#include <arbor/sdk/task.hpp>

#include <cstdint>
#include <optional>

namespace arbor::importers {

struct CompressedRange {
    uint64_t offset = 0;                    // where the compressed stream starts
    std::optional<uint64_t> size;           // its length when the header says; else to end of file
    uint64_t skip = 0;                      // decoded bytes to discard before the voxels
    const char *format = "gzip";            // "gzip" or "zlib", for messages
    const char *needs = "the header needs"; // who asks for the decoded size, for messages
};

// Fills dest[0, size) with decoded bytes.  Both zlib and gzip wrappers are
// accepted (zlib detects which), as are several concatenated gzip members.
// Throws ARBOR_ERROR_FORMAT when the stream is corrupt or ends early (the
// message says how many bytes were decoded), ARBOR_ERROR_CANCELLED on cancel.
void inflate_into(const DataFile &file, const CompressedRange &range, void *dest, uint64_t size,
                  const sdk::Task &task);

} // namespace arbor::importers
