#include "channel_services.hpp"

#include <algorithm>
#include <cstring>

namespace arbor::plugin_host {

using namespace isolation;

ChannelLog::ChannelLog(ChannelHeader *header) : header_(header)
{
    host_.struct_size = sizeof host_;
    host_.abi_version = ARBOR_ABI_VERSION_INIT;
    host_.name = "Arbor (isolated plugin process)";
    host_.version = ARBOR_HOST_VERSION;
    host_.host_data = this;
    host_.log = &c_log;
    host_.get_extension = &c_extension;
}

void ChannelLog::c_log(const arbor_host *host, arbor_log_level level, const char *message)
{
    if (!host || !host->host_data || !message)
        return;
    auto *self = static_cast<ChannelLog *>(host->host_data);
    ChannelHeader &h = *self->header_;
    const uint32_t length = static_cast<uint32_t>(strnlen(message, 4096));
    std::lock_guard lock(self->mutex_);
    const uint64_t written = h.log_written.load(std::memory_order_relaxed);
    const uint64_t read = h.log_read.load(std::memory_order_acquire);
    if (written - read + 8 + length > kLogBytes) {
        h.log_dropped.fetch_add(1);
        return;
    }
    uint8_t record[8];
    for (int b = 0; b < 4; ++b) {
        record[b] = static_cast<uint8_t>(level >> (8 * b));
        record[4 + b] = static_cast<uint8_t>(length >> (8 * b));
    }
    uint64_t at = written;
    for (uint8_t byte : record)
        h.log[at++ % kLogBytes] = static_cast<char>(byte);
    for (uint32_t i = 0; i < length; ++i)
        h.log[at++ % kLogBytes] = message[i];
    h.log_written.store(at, std::memory_order_release);
}

ChannelTask::ChannelTask(ChannelHeader *header, uint8_t *window) : header_(header), window_(window)
{
    task_.struct_size = sizeof task_;
    task_.host_data = this;
    task_.progress = &c_progress;
    task_.cancelled = &c_cancelled;
    task_.allocate = &c_allocate;
}

arbor_bool32 ChannelTask::c_progress(arbor_task *task, double fraction, const char *stage)
{
    auto *self = static_cast<ChannelTask *>(task->host_data);
    ChannelHeader &h = *self->header_;
    {
        std::lock_guard lock(self->progress_mutex_);
        const uint32_t seq = h.progress_seq.load(std::memory_order_relaxed);
        h.progress_seq.store(seq + 1, std::memory_order_release); // odd: writing
        std::atomic_thread_fence(std::memory_order_release);
        h.progress = fraction;
        if (stage) {
            const std::size_t n = strnlen(stage, sizeof h.stage - 1);
            std::memcpy(h.stage, stage, n);
            h.stage[n] = '\0';
        }
        h.progress_seq.store(seq + 2, std::memory_order_release);
    }
    h.heartbeat.fetch_add(1, std::memory_order_relaxed);
    return h.cancel.load(std::memory_order_acquire) != 0;
}

arbor_bool32 ChannelTask::c_cancelled(arbor_task *task)
{
    ChannelHeader &h = *static_cast<ChannelTask *>(task->host_data)->header_;
    h.heartbeat.fetch_add(1, std::memory_order_relaxed);
    return h.cancel.load(std::memory_order_acquire) != 0;
}

void *ChannelTask::allocate(uint64_t size)
{
    ChannelHeader &h = *header_;
    if (size == 0 || size > (uint64_t{1} << 34))
        return nullptr;
    uint64_t top = h.allocate_top.load();
    for (;;) {
        if (top < size)
            return nullptr;
        const uint64_t next = (top - size) & ~uint64_t{63};
        if (next < h.allocate_limit)
            return nullptr;
        if (h.allocate_top.compare_exchange_weak(top, next)) {
            std::memset(window_ + next, 0, size);
            return window_ + next;
        }
    }
}

void *ChannelTask::c_allocate(arbor_task *task, uint64_t size)
{
    return static_cast<ChannelTask *>(task->host_data)->allocate(size);
}

} // namespace arbor::plugin_host
