// fuzz_support.hpp - what every harness shares: the fuzz input as a file for
// parsers that read files, and the one rule the harnesses check.
//
// The rule (README "Errors"): bad input gets a clear message, never a crash,
// a hang or a huge allocation.  A parser refuses input by throwing the
// exception type its header documents; anything else escaping it (a
// std::out_of_range from a library, a JSON type error, ...) is a finding,
// reported by finding() as an abort that libFuzzer and the replay driver
// both count as a failure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::fuzz {

// A folder of this process's own under $TMPDIR (or /tmp), removed at exit.
const std::filesystem::path &scratch_folder();

// Writes `data` to scratch_folder() / `name`, replacing what was there.
std::filesystem::path write_input(const std::string &name, const uint8_t *data, std::size_t size);

// Splits the input at every `separator` (harnesses whose input is several
// files).
std::vector<std::string_view> split_input(const uint8_t *data, std::size_t size, std::string_view separator);

// Prints "FINDING: <what>" to stderr and aborts.
[[noreturn]] void finding(const std::string &what);

// For catch (...) after the documented refusals: names the unexpected
// exception's type and message, then aborts.
[[noreturn]] void unexpected_exception(std::exception_ptr e);

} // namespace arbor::fuzz
