// nrrd_header.hpp - the header of a NRRD file ("nearly raw raster data",
// http://teem.sourceforge.net/nrrd/format.html), parsed into the grid Arbor
// needs (LPS geometry) and where and how the voxel data are stored.
#pragma once

#include "voxel_grid.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace arbor::importers {

enum class NrrdEncoding { raw, gzip, ascii };

struct NrrdHeader {
    VoxelGrid grid;       // dimension 2 becomes one slice: dims {x, y, 1}
    ValueMapping mapping; // from the arbor_value_* key/value pairs
    NrrdEncoding encoding = NrrdEncoding::raw;
    std::endian byte_order = std::endian::little;
    std::string data_file; // as written; "" when the data follow the header
    int64_t line_skip = 0;
    int64_t byte_skip = 0; // -1: the raw data are the last bytes of the file
};

// True when `head` starts with the magic "NRRD000" and a version digit.
bool has_nrrd_magic(std::string_view head);

// Length of the header at the start of `text` including the blank line that
// ends it, or nullopt when `text` holds no blank line.
std::optional<std::size_t> nrrd_header_length(std::string_view text);

// Parses a header (magic line first, up to the blank line or the end of the
// text).  Throws arbor::sdk::Error naming `file_name` and the problem:
// ARBOR_ERROR_FORMAT for malformed headers, ARBOR_ERROR_UNSUPPORTED for valid
// NRRD that Arbor does not read (64-bit types, bzip2, vector axes...).
NrrdHeader parse_nrrd_header(std::string_view text, std::string_view file_name);

} // namespace arbor::importers
