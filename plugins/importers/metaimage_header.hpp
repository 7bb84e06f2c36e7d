// metaimage_header.hpp - the "Key = Value" header of an ITK MetaImage file
// (.mha with the data after it, .mhd with a separate data file), parsed into
// the grid Arbor needs and where and how the voxel data are stored.
#pragma once

#include "voxel_grid.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace arbor::importers {

struct MetaImageHeader {
    VoxelGrid grid; // LPS (MetaImage physical space is ITK's); NDims 2 is one slice
    std::endian byte_order = std::endian::little;
    bool binary = true;      // false: voxel values written as text
    bool compressed = false; // zlib (or gzip) stream
    std::optional<uint64_t> compressed_size;
    int64_t header_size = 0; // bytes to skip from the start of the data file; -1: data at its end
    std::string data_file;   // as written; "" for LOCAL (the data follow the header)
    std::size_t header_length = 0; // bytes up to and including the ElementDataFile line
};

// Bytes up to and including the line break of the ElementDataFile line (the
// last line of every MetaImage header), or nullopt when `text` holds none.
std::optional<std::size_t> metaimage_header_length(std::string_view text);

// True when `head` starts with MetaImage "Key = Value" lines that include
// NDims and DimSize or ElementType.
bool looks_like_metaimage(std::string_view head);

// Parses the header up to its ElementDataFile line.  Throws
// arbor::sdk::Error naming `file_name` and the problem: ARBOR_ERROR_FORMAT for
// malformed headers, ARBOR_ERROR_UNSUPPORTED for valid MetaImage that Arbor
// does not read (NDims 4, several channels, file lists...).
MetaImageHeader parse_metaimage_header(std::string_view text, std::string_view file_name);

} // namespace arbor::importers
