// process_run.hpp - runs a program as a child process (posix_spawn, no
// shell) with its output discarded, and times it from start to exit: what a
// benchmark of whole `arbor` commands measures, import and writing included.
#pragma once

#include <string>
#include <vector>

namespace arbor::bench {

struct ProcessRun {
    bool ok = false;      // started and exited with status 0
    double seconds = 0.0; // wall time from spawning to its exit
    std::string error;    // why not ok
};

// argv[0] is the program's path.
ProcessRun run_process(const std::vector<std::string> &argv);

} // namespace arbor::bench
