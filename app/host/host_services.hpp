// host_services.hpp - what the host gives plugins: the arbor_host record
// (logging, identity) and arbor_task records (progress, cancellation, memory
// for outputs).
//
// Every library and every instance gets its own arbor_host, so the log can
// say which plugin spoke.  Tasks report progress to a ProgressSink (the CLI's
// terminal bar, later the GUI) and see cancellation requested from anywhere
// (Ctrl-C in the CLI sets the global flag).
#pragma once

#include <arbor/host.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace arbor {

// Host log: messages at or above the level go to stderr.
void set_log_level(arbor_log_level level);
arbor_log_level log_level();
void log_message(arbor_log_level level, const std::string &source, const std::string &message);

// An arbor_host whose log messages carry `source` (a plugin id or a path).
class HostIdentity {
public:
    explicit HostIdentity(std::string source);
    HostIdentity(const HostIdentity &) = delete;
    HostIdentity &operator=(const HostIdentity &) = delete;
    const arbor_host *get() const { return &host_; }
    const std::string &source() const { return source_; }

private:
    arbor_host host_{};
    std::string source_;
};

// Receives progress of long calls; implementations must be thread-safe.
class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    virtual void report(const std::string &stage, double fraction) = 0;
    virtual void finish() = 0;
};

// Process-wide cancellation request (set by the CLI's SIGINT handler).
void request_cancellation();
bool cancellation_requested();
void reset_cancellation();

// One long-running plugin call.  Owns the memory plugins obtain through
// allocate(), up to a limit; the memory lives as long as the Task.
class Task {
public:
    explicit Task(ProgressSink *sink = nullptr, uint64_t memory_limit = uint64_t{1} << 34);
    ~Task();
    Task(const Task &) = delete;
    Task &operator=(const Task &) = delete;

    arbor_task *get() { return &task_; }
    void cancel() { cancelled_ = true; }
    bool cancelled() const { return cancelled_ || cancellation_requested(); }
    uint64_t allocated_bytes() const { return allocated_; }

private:
    static arbor_bool32 c_progress(arbor_task *task, double fraction, const char *stage);
    static arbor_bool32 c_cancelled(arbor_task *task);
    static void *c_allocate(arbor_task *task, uint64_t size);

    arbor_task task_{};
    ProgressSink *sink_;
    std::atomic<bool> cancelled_{false};
    std::mutex mutex_;
    std::string stage_;
    uint64_t limit_;
    uint64_t allocated_ = 0;
    std::vector<void *> blocks_;
};

} // namespace arbor
