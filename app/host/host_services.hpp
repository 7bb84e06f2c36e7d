// host_services.hpp - what the host gives plugins: the arbor_host record
// (logging, identity) and arbor_task records (progress, cancellation, memory
// for outputs).
//
// Every library and every instance gets its own arbor_host, so the log can
// say which plugin spoke, and an instance's messages can be routed to the log
// of the job using it.  Tasks report progress to a ProgressSink (the CLI's
// terminal bar, a pipeline job) and see cancellation through the stop token
// of whoever started the call; there is no process-wide cancel flag.
#pragma once

#include <arbor/host.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stop_token>
#include <string>
#include <vector>

namespace arbor {

// Host log: messages at or above the level go to stderr.
void set_log_level(arbor_log_level level);
arbor_log_level log_level();
void log_message(arbor_log_level level, const std::string &source, const std::string &message);

// Receives log messages (a job's log); implementations must be thread-safe.
class LogSink {
public:
    virtual ~LogSink() = default;
    virtual void write(arbor_log_level level, const std::string &source, const std::string &message) = 0;
};

// An arbor_host whose log messages carry `source` (a plugin id or a path).
// They go to the sink set with route_log(), or to the host log.
class HostIdentity {
public:
    explicit HostIdentity(std::string source);
    HostIdentity(const HostIdentity &) = delete;
    HostIdentity &operator=(const HostIdentity &) = delete;
    const arbor_host *get() const { return &host_; }
    const std::string &source() const { return source_; }
    // nullptr: back to the host log.  The sink must outlive its routing.
    void route_log(LogSink *sink) { sink_ = sink; }
    void log(arbor_log_level level, const std::string &message) const;

private:
    arbor_host host_{};
    std::string source_;
    std::atomic<LogSink *> sink_{nullptr};
};

// Receives progress of long calls; implementations must be thread-safe.
class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    virtual void report(const std::string &stage, double fraction) = 0;
    virtual void finish() = 0;
};

// One long-running plugin call.  Owns the memory plugins obtain through
// allocate(), up to a limit; the memory lives as long as the Task.  The call
// is cancelled by cancel() or by a stop request on `stop`.
class Task {
public:
    explicit Task(ProgressSink *sink = nullptr, std::stop_token stop = {},
                  uint64_t memory_limit = uint64_t{1} << 34);
    ~Task();
    Task(const Task &) = delete;
    Task &operator=(const Task &) = delete;

    arbor_task *get() { return &task_; }
    void cancel() { cancelled_ = true; }
    bool cancelled() const { return cancelled_ || stop_.stop_requested(); }
    uint64_t allocated_bytes() const { return allocated_; }

private:
    static arbor_bool32 c_progress(arbor_task *task, double fraction, const char *stage);
    static arbor_bool32 c_cancelled(arbor_task *task);
    static void *c_allocate(arbor_task *task, uint64_t size);

    arbor_task task_{};
    ProgressSink *sink_;
    std::stop_token stop_;
    std::atomic<bool> cancelled_{false};
    std::mutex mutex_;
    std::string stage_;
    uint64_t limit_;
    uint64_t allocated_ = 0;
    std::vector<void *> blocks_;
};

} // namespace arbor
