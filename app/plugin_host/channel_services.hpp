// channel_services.hpp - what an isolated plugin gets from its process in
// place of the host's services: an arbor_host whose log goes into the
// channel's log ring, and an arbor_task whose progress, cancellation and
// memory live in the channel's header and window (host/isolation_wire.hpp).
#pragma once

#include "host/isolation_wire.hpp"

#include <arbor/arbor.h>

#include <mutex>

namespace arbor::plugin_host {

class ChannelLog {
public:
    explicit ChannelLog(isolation::ChannelHeader *header);
    ChannelLog(const ChannelLog &) = delete;
    ChannelLog &operator=(const ChannelLog &) = delete;
    const arbor_host *get() const { return &host_; }

private:
    static void c_log(const arbor_host *host, arbor_log_level level, const char *message);
    static const void *c_extension(const arbor_host *, const char *) { return nullptr; }
    arbor_host host_{};
    isolation::ChannelHeader *header_;
    std::mutex mutex_;
};

class ChannelTask {
public:
    ChannelTask(isolation::ChannelHeader *header, uint8_t *window);
    ChannelTask(const ChannelTask &) = delete;
    ChannelTask &operator=(const ChannelTask &) = delete;
    arbor_task *get() { return &task_; }
    // task->allocate, usable by the server too (the control points' copy).
    void *allocate(uint64_t size);
    uint8_t *window() const { return window_; }

private:
    static arbor_bool32 c_progress(arbor_task *task, double fraction, const char *stage);
    static arbor_bool32 c_cancelled(arbor_task *task);
    static void *c_allocate(arbor_task *task, uint64_t size);
    arbor_task task_{};
    isolation::ChannelHeader *header_;
    uint8_t *window_;
    std::mutex progress_mutex_;
};

} // namespace arbor::plugin_host
