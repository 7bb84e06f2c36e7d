// isolation_flags.hpp - how plugins run, decided before they load (their
// parameters become flags, so the choice cannot wait for the parser):
//
//   --isolate all|third-party|none   which libraries run in a process of
//                                    their own (default third-party: every
//                                    library outside Arbor's plugin folder)
//   --plugin-timeout SECONDS         an isolated call without a sign of life
//                                    for this long is hung (default 60)
//
// Later sources win: the defaults, ARBOR_ISOLATE and ARBOR_PLUGIN_TIMEOUT,
// the "plugins" object of a session named on the command line (`run
// --session s.json`, `view s.json`), the flags.
#pragma once

#include "host/plugin_registry.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace arbor::cli {

struct IsolationChoice {
    IsolationMode mode = IsolationMode::ThirdParty;
    double timeout_seconds = 60;
};

// Throws UsageError for a value that is not one.
IsolationChoice isolation_from_command_line(int argc, char **argv);

// The two flags on `app` (for --help, and so the parser accepts them
// before or after the command).
void add_isolation_options(CLI::App &app);

} // namespace arbor::cli
