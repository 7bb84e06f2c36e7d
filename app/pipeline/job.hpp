// job.hpp - one stage computed on its own thread: its stop source (cancel
// one job, the others go on), its progress and its log, and its result or
// error once it ends.  A front watches jobs (a progress bar per job, a log
// panel) and waits on them; the pipeline (pipeline.hpp) creates them.
#pragma once

#include "stage_graph.hpp"

#include "host/host_services.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <stop_token>
#include <string>
#include <vector>

namespace arbor::pipeline {

enum class JobState { Waiting, Running, Done, Failed, Cancelled };
const char *job_state_name(JobState state);

struct LogEntry {
    arbor_log_level level = ARBOR_LOG_INFO;
    std::string source, message;
};

class Job final : public ProgressSink, public LogSink {
public:
    // `forward_progress`, `forward_log`: where the job's progress and log also
    // go (a terminal); may be null (the log then goes to the host log).
    Job(Stage stage, uint64_t serial, ProgressSink *forward_progress, LogSink *forward_log);
    // A job that ended before it began: a result the pipeline already had.
    static std::shared_ptr<Job> finished(Stage stage, std::shared_ptr<const void> result);

    Stage stage() const { return stage_; }
    uint64_t serial() const { return serial_; }
    JobState state() const;
    bool ended() const;
    // The current activity ("join and split trees") and its fraction.
    std::string activity() const;
    double fraction() const;
    std::vector<LogEntry> log() const;
    // The failure's message (empty unless Failed).
    std::string error() const;

    void cancel() { stop_.request_stop(); }
    std::stop_token stop_token() const { return stop_.get_token(); }

    // Blocks until the job ends; its result, or throws its error (Cancelled
    // when it was cancelled).
    std::shared_ptr<const void> wait() const;
    // The same, but gives up with Cancelled when `waiter` asks to stop (a
    // job waiting on its upstream job).
    std::shared_ptr<const void> wait(std::stop_token waiter) const;
    bool wait_for(std::chrono::milliseconds timeout) const;

    // ProgressSink, LogSink (the stage's code and its plugins report here).
    void report(const std::string &stage, double fraction) override;
    void finish() override;
    void write(arbor_log_level level, const std::string &source, const std::string &message) override;

    // Used by the pipeline's worker.
    void start();
    void succeed(std::shared_ptr<const void> result);
    void fail(std::exception_ptr error);
    void cancelled();

private:
    std::shared_ptr<const void> result_locked(std::unique_lock<std::mutex> &lock, bool gave_up) const;
    void end(JobState state);

    const Stage stage_;
    const uint64_t serial_;
    ProgressSink *forward_progress_;
    LogSink *forward_log_;
    std::stop_source stop_;

    mutable std::mutex mutex_;
    mutable std::condition_variable_any ended_cv_;
    JobState state_ = JobState::Waiting;
    std::string activity_;
    double fraction_ = 0.0;
    std::vector<LogEntry> log_;
    std::shared_ptr<const void> result_;
    std::exception_ptr error_;
};

} // namespace arbor::pipeline
