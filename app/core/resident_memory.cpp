#include "resident_memory.hpp"

#include <fstream>
#include <string>

namespace arbor {

namespace {

// The value of a "Key:  123 kB" line of /proc/self/status, in bytes.
uint64_t status_bytes(const char *wanted)
{
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == wanted) {
            uint64_t kb = 0;
            status >> kb;
            return kb * 1024;
        }
        std::getline(status, key);
    }
    return 0;
}

} // namespace

uint64_t resident_bytes()
{
    return status_bytes("VmRSS:");
}

uint64_t peak_resident_bytes()
{
    return status_bytes("VmHWM:");
}

void reset_peak_resident_bytes()
{
    // Writing 5 to clear_refs resets VmHWM to the current resident size.
    std::ofstream("/proc/self/clear_refs") << "5";
}

} // namespace arbor
