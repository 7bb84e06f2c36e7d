#include "host_services.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace arbor {

namespace {

std::atomic<arbor_log_level> g_level{ARBOR_LOG_INFO};
std::mutex g_log_mutex;

const char *level_name(arbor_log_level level)
{
    switch (level) {
    case ARBOR_LOG_DEBUG: return "debug";
    case ARBOR_LOG_INFO: return "info";
    case ARBOR_LOG_WARNING: return "warning";
    default: return "error";
    }
}

void c_log(const arbor_host *host, arbor_log_level level, const char *message)
{
    const auto *self = host ? static_cast<const HostIdentity *>(host->host_data) : nullptr;
    const std::string text = message ? message : "(null message)";
    if (self)
        self->log(level, text);
    else
        log_message(level, "plugin", text);
}

const void *c_get_extension(const arbor_host *, const char *)
{
    return nullptr;
}

} // namespace

void set_log_level(arbor_log_level level)
{
    g_level = level;
}

arbor_log_level log_level()
{
    return g_level;
}

void log_message(arbor_log_level level, const std::string &source, const std::string &message)
{
    if (level < g_level)
        return;
    std::lock_guard lock(g_log_mutex);
    if (source.empty())
        std::fprintf(stderr, "arbor: %s: %s\n", level_name(level), message.c_str());
    else
        std::fprintf(stderr, "arbor: %s: [%s] %s\n", level_name(level), source.c_str(),
                     message.c_str());
}

HostIdentity::HostIdentity(std::string source) : source_(std::move(source))
{
    host_.struct_size = sizeof(arbor_host);
    host_.abi_version = ARBOR_ABI_VERSION_INIT;
    host_.name = "Arbor";
    host_.version = ARBOR_HOST_VERSION;
    host_.host_data = this;
    host_.log = &c_log;
    host_.get_extension = &c_get_extension;
}

void HostIdentity::log(arbor_log_level level, const std::string &message) const
{
    if (LogSink *sink = sink_.load())
        sink->write(level, source_, message);
    else
        log_message(level, source_, message);
}

Task::Task(ProgressSink *sink, std::stop_token stop, uint64_t memory_limit)
    : sink_(sink), stop_(std::move(stop)), limit_(memory_limit)
{
    task_.struct_size = sizeof(arbor_task);
    task_.host_data = this;
    task_.progress = &c_progress;
    task_.cancelled = &c_cancelled;
    task_.allocate = &c_allocate;
}

Task::~Task()
{
    for (void *p : blocks_)
        std::free(p);
    if (sink_)
        sink_->finish();
}

arbor_bool32 Task::c_progress(arbor_task *task, double fraction, const char *stage)
{
    if (!task || !task->host_data)
        return 0;
    auto *self = static_cast<Task *>(task->host_data);
    if (self->sink_) {
        std::lock_guard lock(self->mutex_);
        if (stage)
            self->stage_ = stage;
        if (!(fraction >= 0.0))
            fraction = 0.0;
        self->sink_->report(self->stage_, fraction > 1.0 ? 1.0 : fraction);
    }
    return self->cancelled() ? 1 : 0;
}

arbor_bool32 Task::c_cancelled(arbor_task *task)
{
    if (!task || !task->host_data)
        return 0;
    return static_cast<Task *>(task->host_data)->cancelled() ? 1 : 0;
}

void *Task::c_allocate(arbor_task *task, uint64_t size)
{
    if (!task || !task->host_data || size == 0)
        return nullptr;
    auto *self = static_cast<Task *>(task->host_data);
    std::lock_guard lock(self->mutex_);
    if (size > self->limit_ || self->allocated_ > self->limit_ - size)
        return nullptr;
    const uint64_t rounded = (size + 63) / 64 * 64;
    void *p = std::aligned_alloc(64, rounded);
    if (!p)
        return nullptr;
    std::memset(p, 0, rounded);
    self->blocks_.push_back(p);
    self->allocated_ += size;
    return p;
}

} // namespace arbor
