#include "conformance_cancel.hpp"

#include "host_services.hpp"

#include <condition_variable>
#include <mutex>
#include <thread>

namespace arbor {

CancelOutcome cancel_mid_call(const std::function<arbor_status(arbor_task *)> &call,
                              std::chrono::milliseconds after)
{
    using Clock = std::chrono::steady_clock;
    Task task;
    std::mutex mutex;
    std::condition_variable returned;
    bool done = false;
    Clock::time_point cancelled_at{};
    std::thread canceller([&] {
        std::unique_lock lock(mutex);
        if (!returned.wait_for(lock, after, [&] { return done; })) {
            cancelled_at = Clock::now();
            task.cancel();
        }
    });
    const Clock::time_point start = Clock::now();
    CancelOutcome out;
    out.status = call(task.get());
    const Clock::time_point end = Clock::now();
    {
        std::lock_guard lock(mutex);
        done = true;
    }
    returned.notify_all();
    canceller.join();
    const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
    out.seconds = seconds(end - start);
    out.cancelled = cancelled_at != Clock::time_point{};
    if (out.cancelled)
        out.seconds_after = seconds(end - cancelled_at);
    return out;
}

} // namespace arbor
