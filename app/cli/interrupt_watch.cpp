#include "interrupt_watch.hpp"

#include <csignal>
#include <ctime>
#include <unistd.h>

namespace arbor::cli {

InterruptWatch::InterruptWatch(std::function<void()> on_interrupt) : on_interrupt_(std::move(on_interrupt))
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    watcher_ = std::jthread([this, set](std::stop_token stop) {
        const timespec tick{0, 100'000'000}; // look at `stop` ten times a second
        while (!stop.stop_requested()) {
            if (sigtimedwait(&set, nullptr, &tick) != SIGINT)
                continue;
            if (interrupted_.exchange(true))
                _exit(130);
            on_interrupt_();
        }
    });
}

InterruptWatch::~InterruptWatch()
{
    watcher_.request_stop();
    watcher_.join();
}

} // namespace arbor::cli
