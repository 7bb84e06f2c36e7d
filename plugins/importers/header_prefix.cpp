// header_prefix.cpp - see header_prefix.hpp.
#include "header_prefix.hpp"

#include <arbor/sdk/error.hpp>

namespace arbor::importers {

HeaderPrefix read_header_prefix(const DataFile &file, HeaderEnd find_end, std::size_t max_bytes)
{
    constexpr std::size_t kChunk = 64 * 1024;
    HeaderPrefix prefix;
    while (prefix.text.size() < max_bytes) {
        const std::size_t old = prefix.text.size();
        const std::size_t want = std::min(kChunk, max_bytes - old);
        prefix.text.resize(old + want);
        const std::size_t got = file.read_at(old, prefix.text.data() + old, want);
        prefix.text.resize(old + got);
        if (const std::optional<std::size_t> end = find_end(prefix.text)) {
            prefix.text.resize(*end);
            prefix.ended = true;
            return prefix;
        }
        if (got < want)
            return prefix; // end of file
    }
    if (file.size() <= max_bytes)
        return prefix;
    sdk::fail(ARBOR_ERROR_FORMAT, "the header of " + file.name() +
                                      " does not end within its first " +
                                      std::to_string(max_bytes) + " bytes");
}

} // namespace arbor::importers
