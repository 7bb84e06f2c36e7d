// available_memory.hpp - how much memory a computation may still allocate,
// so that a volume too large for this machine is refused with a figure
// before anything is allocated, not killed by the kernel half-way through.
#pragma once

#include <cstdint>
#include <string>

namespace arbor {

// Bytes the process can allocate now without swapping or being killed: the
// kernel's MemAvailable, lowered to what a cgroup (v2) memory limit leaves.
// The environment variable ARBOR_MEMORY_AVAILABLE (bytes) overrides it, for
// tests and for sharing a machine; a value that is not a byte count throws
// std::invalid_argument.  0 when nothing says (no /proc).
uint64_t available_memory_bytes();

// ARBOR_MEMORY_AVAILABLE's text as bytes: digits, with a decimal point or
// an exponent if wanted ("3300000000", "3.3e9"); anything else throws
// std::invalid_argument naming the value.
uint64_t memory_override_bytes(const char *text);

// "" when `needed` bytes fit in what is available; otherwise a sentence:
// "<what> needs about 15.7 GB (<detail>), and 9.8 GB of memory is available".
std::string check_memory(uint64_t needed, const std::string &what, const std::string &detail);

} // namespace arbor
