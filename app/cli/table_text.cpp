#include "table_text.hpp"

namespace arbor::cli {

std::string clip(const std::string &s, std::size_t width)
{
    if (s.size() <= width)
        return s;
    std::size_t end = width - 1;
    while (end > 0 && (static_cast<unsigned char>(s[end]) & 0xC0) == 0x80)
        --end;
    return s.substr(0, end) + "~";
}

} // namespace arbor::cli
