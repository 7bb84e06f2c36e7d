// conformance_checks.hpp - the individual conformance checks, run inside the
// child process that conformance.cpp forks.  Results go to a CheckSink.
#pragma once

#include <arbor/arbor.h>

#include <filesystem>
#include <string>

namespace arbor {

class CheckSink {
public:
    virtual ~CheckSink() = default;
    // Announces the check about to run (reported if the process dies in it).
    virtual void begin(const std::string &plugin, const std::string &check) = 0;
    virtual void result(const std::string &plugin, const std::string &check, bool passed,
                        const std::string &detail) = 0;
};

// Entry-level checks that concern no single plugin.
void check_entry(const arbor_plugin_entry &entry, const arbor_host *host, CheckSink &sink);

// All checks of one plugin of the library; `scratch` is an empty folder for
// test files.
void check_plugin(const arbor_plugin_entry &entry, const arbor_host *host,
                  const arbor_plugin_descriptor &descriptor, const std::filesystem::path &scratch,
                  CheckSink &sink);

} // namespace arbor
