#include "available_memory.hpp"

#include "resident_memory.hpp"
#include "volume_header.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

namespace arbor {

namespace {

// A positive integer from a whole file ("max" and anything else: 0).
uint64_t file_number(const char *path)
{
    std::ifstream in(path);
    std::string text;
    if (!(in >> text) || text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
        return 0;
    return std::strtoull(text.c_str(), nullptr, 10);
}

} // namespace

uint64_t memory_override_bytes(const char *text)
{
    // strtod alone would take "0x10", "inf" or " 5"; only digits, one point
    // and an exponent are a byte count here.
    const std::string s = text;
    const bool plain = !s.empty() && s.find_first_not_of("0123456789.eE+-") == std::string::npos &&
                       std::isdigit(static_cast<unsigned char>(s[0]));
    char *end = nullptr;
    const double v = plain ? std::strtod(text, &end) : -1.0;
    if (!plain || end == text || *end != '\0' || !(v >= 0) ||
        v >= static_cast<double>(std::numeric_limits<uint64_t>::max()))
        throw std::invalid_argument("ARBOR_MEMORY_AVAILABLE is \"" + s +
                                    "\": expected the bytes available, such as 3300000000 or 3.3e9");
    return static_cast<uint64_t>(v);
}

uint64_t available_memory_bytes()
{
    if (const char *env = std::getenv("ARBOR_MEMORY_AVAILABLE"))
        return memory_override_bytes(env);
    uint64_t available = proc_kilobytes_field("/proc/meminfo", "MemAvailable:");
    // The cgroup this process is in (containers, systemd slices): its limit
    // less what the group already uses.
    const uint64_t limit = file_number("/sys/fs/cgroup/memory.max");
    if (limit > 0) {
        const uint64_t used = file_number("/sys/fs/cgroup/memory.current");
        const uint64_t left = limit > used ? limit - used : 0;
        available = available == 0 ? left : std::min(available, left);
    }
    return available;
}

std::string check_memory(uint64_t needed, const std::string &what, const std::string &detail)
{
    const uint64_t available = available_memory_bytes();
    if (available == 0 || needed <= available)
        return "";
    return what + " needs about " + format_bytes(needed) + (detail.empty() ? "" : " (" + detail + ")") +
           ", and " + format_bytes(available) + " of memory is available";
}

} // namespace arbor
