// resident_memory.hpp - how much memory this process holds, from the kernel's
// accounting (/proc/self/status): the resident size now, its peak so far, and
// a way to restart the peak, so that benchmarks and `--timings` can report
// what one computation needed.
#pragma once

#include <cstdint>

namespace arbor {

// The value of a "Key:  123 kB" line of a /proc file (status, meminfo), in
// bytes; 0 where the file or the key is missing.  `key` includes the colon.
uint64_t proc_kilobytes_field(const char *path, const char *key);

// Resident set size now (VmRSS), in bytes; 0 where the kernel does not say.
uint64_t resident_bytes();

// Peak resident set size of this process so far (VmHWM), in bytes; 0 where
// the kernel does not say.
uint64_t peak_resident_bytes();

// Restarts the peak at the current resident size (benchmarks measuring one
// volume after another).  The kernel may ignore it: compare
// peak_resident_bytes() with resident_bytes() afterwards to know.
void reset_peak_resident_bytes();

} // namespace arbor
