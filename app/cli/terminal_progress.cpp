#include "terminal_progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace arbor::cli {

TerminalProgress::TerminalProgress()
    : enabled_(isatty(STDERR_FILENO) == 1 && log_level() <= ARBOR_LOG_INFO)
{
}

void TerminalProgress::report(const std::string &stage, double fraction)
{
    if (!enabled_)
        return;
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    const std::optional<double> left =
        clock_.observe(stage, fraction, std::chrono::duration<double>(now.time_since_epoch()).count());
    if (shown_ && fraction < 1.0 && now - last_ < std::chrono::milliseconds(100))
        return;
    last_ = now;
    shown_ = true;
    std::fprintf(stderr, "\r\033[K  %s %3d%%%s%s", stage.empty() ? "working" : stage.c_str(),
                 static_cast<int>(fraction * 100.0 + 0.5), left ? ", " : "",
                 left ? pipeline::format_time_left(*left).c_str() : "");
    std::fflush(stderr);
}

void TerminalProgress::finish()
{
    std::lock_guard lock(mutex_);
    if (enabled_ && shown_) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
    shown_ = false;
}

} // namespace arbor::cli
