// header_prefix.hpp - reads the text header at the start of a file, and no
// more: chunk by chunk until the format's end marker turns up, with a cap so
// that a file without one cannot make the importer read (or keep) it all.
#pragma once

#include "data_file.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace arbor::importers {

struct HeaderPrefix {
    std::string text;   // the header, end marker included when `ended`
    bool ended = false; // false: the file ended before an end marker
};

// Length of the header at the start of `text` (end marker included), or
// nullopt when `text` holds no complete header yet.
using HeaderEnd = std::optional<std::size_t> (*)(std::string_view text);

inline constexpr std::size_t kMaxHeaderBytes = std::size_t{4} << 20;

// Throws ARBOR_ERROR_FORMAT when kMaxHeaderBytes pass without an end marker.
HeaderPrefix read_header_prefix(const DataFile &file, HeaderEnd find_end,
                                std::size_t max_bytes = kMaxHeaderBytes);

} // namespace arbor::importers
