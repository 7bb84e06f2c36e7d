// terminal_progress.hpp - progress of long plugin calls on the terminal:
// one self-overwriting line on stderr, at most ten updates a second, with
// the time the stage has left once it can be told, and nothing at all when
// stderr is not a terminal (logs and CI stay clean).
#pragma once

#include "host/host_services.hpp"
#include "pipeline/time_left.hpp"

#include <chrono>
#include <mutex>
#include <string>

namespace arbor::cli {

class TerminalProgress : public ProgressSink {
public:
    TerminalProgress();
    void report(const std::string &stage, double fraction) override;
    void finish() override;

private:
    std::mutex mutex_;
    bool enabled_;
    bool shown_ = false;
    std::chrono::steady_clock::time_point last_;
    pipeline::StageClock clock_;
};

} // namespace arbor::cli
