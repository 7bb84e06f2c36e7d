#include "job.hpp"

#include "core/cancelled.hpp"

namespace arbor::pipeline {

namespace {

constexpr std::size_t kMaxLogEntries = 1000; // a noisy plugin cannot grow a job without bound

} // namespace

const char *job_state_name(JobState state)
{
    switch (state) {
    case JobState::Waiting: return "waiting";
    case JobState::Running: return "running";
    case JobState::Done: return "done";
    case JobState::Failed: return "failed";
    default: return "cancelled";
    }
}

Job::Job(Stage stage, uint64_t serial, ProgressSink *forward_progress, LogSink *forward_log)
    : stage_(stage), serial_(serial), forward_progress_(forward_progress), forward_log_(forward_log)
{
}

std::shared_ptr<Job> Job::finished(Stage stage, std::shared_ptr<const void> result)
{
    auto job = std::make_shared<Job>(stage, 0, nullptr, nullptr);
    job->result_ = std::move(result);
    job->state_ = JobState::Done;
    job->fraction_ = 1.0;
    return job;
}

JobState Job::state() const
{
    std::lock_guard lock(mutex_);
    return state_;
}

bool Job::ended() const
{
    const JobState s = state();
    return s == JobState::Done || s == JobState::Failed || s == JobState::Cancelled;
}

std::string Job::activity() const
{
    std::lock_guard lock(mutex_);
    return activity_;
}

double Job::fraction() const
{
    std::lock_guard lock(mutex_);
    return fraction_;
}

std::vector<LogEntry> Job::log() const
{
    std::lock_guard lock(mutex_);
    return log_;
}

std::string Job::error() const
{
    std::lock_guard lock(mutex_);
    if (state_ != JobState::Failed || !error_)
        return {};
    try {
        std::rethrow_exception(error_);
    } catch (const std::exception &e) {
        return e.what();
    } catch (...) {
        return "unknown error";
    }
}

std::shared_ptr<const void> Job::result_locked(std::unique_lock<std::mutex> &, bool gave_up) const
{
    if (gave_up || state_ == JobState::Cancelled)
        throw Cancelled();
    if (state_ == JobState::Failed)
        std::rethrow_exception(error_);
    return result_;
}

std::shared_ptr<const void> Job::wait() const
{
    std::unique_lock lock(mutex_);
    ended_cv_.wait(lock, [this] { return state_ != JobState::Waiting && state_ != JobState::Running; });
    return result_locked(lock, false);
}

std::shared_ptr<const void> Job::wait(std::stop_token waiter) const
{
    std::unique_lock lock(mutex_);
    const bool ended =
        ended_cv_.wait(lock, waiter, [this] { return state_ != JobState::Waiting && state_ != JobState::Running; });
    return result_locked(lock, !ended);
}

bool Job::wait_for(std::chrono::milliseconds timeout) const
{
    std::unique_lock lock(mutex_);
    return ended_cv_.wait_for(lock, timeout,
                              [this] { return state_ != JobState::Waiting && state_ != JobState::Running; });
}

void Job::report(const std::string &stage, double fraction)
{
    {
        std::lock_guard lock(mutex_);
        activity_ = stage;
        fraction_ = fraction;
    }
    if (forward_progress_)
        forward_progress_->report(stage, fraction);
}

void Job::finish()
{
    if (forward_progress_)
        forward_progress_->finish();
}

void Job::write(arbor_log_level level, const std::string &source, const std::string &message)
{
    {
        std::lock_guard lock(mutex_);
        if (log_.size() < kMaxLogEntries)
            log_.push_back({level, source, message});
    }
    if (forward_log_)
        forward_log_->write(level, source, message);
    else
        log_message(level, source, message);
}

void Job::start()
{
    std::lock_guard lock(mutex_);
    state_ = JobState::Running;
}

void Job::end(JobState state)
{
    {
        std::lock_guard lock(mutex_);
        state_ = state;
        if (state == JobState::Done)
            fraction_ = 1.0;
    }
    ended_cv_.notify_all();
}

void Job::succeed(std::shared_ptr<const void> result)
{
    {
        std::lock_guard lock(mutex_);
        result_ = std::move(result);
    }
    end(JobState::Done);
}

void Job::fail(std::exception_ptr error)
{
    {
        std::lock_guard lock(mutex_);
        error_ = std::move(error);
    }
    end(JobState::Failed);
}

void Job::cancelled()
{
    end(JobState::Cancelled);
}

} // namespace arbor::pipeline
