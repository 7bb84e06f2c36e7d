// conformance.hpp - `arbor plugin-check`: the checks a plugin author runs
// before shipping.  Loads the library, validates descriptors and parameter
// descriptions, and calls every interface with invalid arguments (expecting
// clean status codes and messages) and with small valid inputs.
//
// Every plugin is checked in a child process, so a plugin that crashes or
// hangs is reported (with the check it was in) instead of taking the checker
// down.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace arbor {

struct ConformanceCheck {
    std::string plugin; // "" for library-level checks
    std::string name;
    bool passed = false;
    std::string detail;
};

struct ConformanceReport {
    std::string library;
    std::vector<ConformanceCheck> checks;
    int failures() const;
    bool passed() const { return !checks.empty() && failures() == 0; }
};

ConformanceReport check_plugin_conformance(const std::filesystem::path &library,
                                           std::chrono::seconds timeout_per_plugin);

} // namespace arbor
