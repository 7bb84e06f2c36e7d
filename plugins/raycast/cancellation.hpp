// cancellation.hpp - a host task polled from worker threads.  Only the
// thread that called the plugin talks to the host (it asks whether the task
// is cancelled and reports progress); workers read the flag it sets.  So no
// host code runs on the pool's threads, whose synchronisation the host's
// tools (ThreadSanitizer) cannot see, and a cancelled call still stops
// within the piece of work each thread is on.
#pragma once

#include <arbor/sdk/task.hpp>

#include <atomic>
#include <thread>

namespace arbor::raycast {

class Cancellation {
public:
    explicit Cancellation(const sdk::Task &task) : task_(task) {}

    // True once the task is cancelled (as far as the calling thread has seen).
    bool stopped()
    {
        if (std::this_thread::get_id() == caller_ && !stopped_.load(std::memory_order_relaxed) && task_.cancelled())
            stopped_.store(true, std::memory_order_relaxed);
        return stopped_.load(std::memory_order_relaxed);
    }
    // Progress in [0, 1], reported when called on the calling thread.
    void progress(double fraction, const char *what) const
    {
        if (std::this_thread::get_id() == caller_)
            task_.progress(fraction, what);
    }
    void throw_if_cancelled() const { task_.throw_if_cancelled(); }

private:
    const sdk::Task &task_;
    const std::thread::id caller_ = std::this_thread::get_id();
    std::atomic<bool> stopped_{false};
};

} // namespace arbor::raycast
