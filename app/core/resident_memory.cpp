#include "resident_memory.hpp"

#include <fstream>
#include <string>

namespace arbor {

uint64_t proc_kilobytes_field(const char *path, const char *wanted)
{
    std::ifstream in(path);
    std::string key;
    while (in >> key) {
        if (key == wanted) {
            uint64_t kb = 0;
            in >> kb;
            return kb * 1024;
        }
        std::getline(in, key);
    }
    return 0;
}

uint64_t resident_bytes()
{
    return proc_kilobytes_field("/proc/self/status", "VmRSS:");
}

uint64_t peak_resident_bytes()
{
    return proc_kilobytes_field("/proc/self/status", "VmHWM:");
}

void reset_peak_resident_bytes()
{
    // Writing 5 to clear_refs resets VmHWM to the current resident size.
    std::ofstream("/proc/self/clear_refs") << "5";
}

} // namespace arbor
