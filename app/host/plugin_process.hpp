// plugin_process.hpp - one running `arbor-plugin-host`: the child process an
// isolated plugin library lives in, its shared arena and its channels
// (isolation_wire.hpp).
//
// A call posts a request on a channel and waits for the reply while it
// forwards the child's progress to the caller's task, passes the task's
// cancellation on, drains the child's log, and watches for the child's
// death.  A call that shows no sign of life (no reply, no progress or
// cancellation poll) for the timeout kills the process.  After a death every
// call on the process fails at once with the reason; whoever owns it starts
// a new one (isolated_library.hpp).
#pragma once

#include "isolation_wire.hpp"

#include <arbor/arbor.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace arbor {

// How isolated plugins run.
struct IsolationSettings {
    std::filesystem::path helper;   // the arbor-plugin-host executable
    double timeout_seconds = 60;    // without a sign of life, a call is hung
    uint64_t memory_limit = 0;      // the child's data limit (RLIMIT_DATA); 0: none
};

class PluginProcess {
public:
    // Starts the helper; throws std::runtime_error when it cannot.
    PluginProcess(const IsolationSettings &settings, const std::string &library_name);
    ~PluginProcess();
    PluginProcess(const PluginProcess &) = delete;
    PluginProcess &operator=(const PluginProcess &) = delete;

    uint8_t *window(uint32_t channel) const;
    uint64_t window_bytes() const { return window_bytes_; }
    isolation::ChannelHeader &header(uint32_t channel) const
    {
        return *reinterpret_cast<isolation::ChannelHeader *>(window(channel));
    }
    // A free instance channel (1..), or 0 when all are taken.
    uint32_t open_channel();
    void close_channel(uint32_t channel);

    // Posts the request written into the channel's request area (size
    // `request_size`) and waits for its reply.  Log messages go to `log`
    // (the instance's arbor_host; may be null), progress and cancellation
    // through `task` (may be null).  Returns "" when the child answered,
    // otherwise why it did not ("crashed (SIGSEGV, ...)").
    std::string call(uint32_t channel, isolation::Op op, uint64_t request_size, arbor_task *task,
                     const arbor_host *log);

    // The two halves of call(): post returns what wait needs.  Several
    // processes can work on posted requests at once (libraries loading).
    uint32_t post(uint32_t channel, isolation::Op op, uint64_t request_size);
    std::string wait(uint32_t channel, uint32_t posted, arbor_task *task, const arbor_host *log);

    bool alive() const { return !dead_.load(); }
    std::string death() const;
    int pid() const { return pid_; }

    // Held around every call on channel 0 (load, create, destroy), which
    // all instances of the library share.
    std::mutex control_mutex;

    // Releases the memory a call's bulk data took past `keep` bytes of bulk.
    void release_bulk(uint32_t channel, uint64_t keep, uint64_t used);

private:
    void mark_dead(const std::string &reason);
    bool reap(bool wait);
    void drain_log(uint32_t channel, const arbor_host *log);

    IsolationSettings settings_;
    std::string name_;
    int pid_ = -1;
    int memfd_ = -1;
    int lifeline_ = -1; // the write end of the child's lifeline pipe
    uint8_t *arena_ = nullptr;
    uint64_t arena_bytes_ = 0, window_bytes_ = 0;
    std::atomic<bool> dead_{false};
    mutable std::mutex mutex_; // death_, channels_, reaping
    std::string death_;
    bool reaped_ = false;
    std::vector<bool> channels_;
};

} // namespace arbor
