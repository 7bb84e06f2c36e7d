// interrupt_watch.hpp - Ctrl-C in the CLI.  SIGINT is blocked in every thread
// and taken by one watcher thread with sigtimedwait, so the reaction runs as
// ordinary code (a signal handler could not safely cancel jobs): the first
// Ctrl-C calls `on_interrupt` (cancel the command's jobs), the second ends
// the process at once with status 130.
#pragma once

#include <atomic>
#include <functional>
#include <thread>

namespace arbor::cli {

class InterruptWatch {
public:
    // Call before any other thread starts: threads inherit the signal mask.
    explicit InterruptWatch(std::function<void()> on_interrupt);
    ~InterruptWatch();
    InterruptWatch(const InterruptWatch &) = delete;
    InterruptWatch &operator=(const InterruptWatch &) = delete;

    bool interrupted() const { return interrupted_; }

private:
    std::function<void()> on_interrupt_;
    std::atomic<bool> interrupted_{false};
    std::jthread watcher_;
};

} // namespace arbor::cli
