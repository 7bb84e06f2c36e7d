#include "plugin_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char **environ;

namespace arbor {

using namespace isolation;

namespace {

const char *describe_signal(int signal)
{
    switch (signal) {
    case SIGSEGV: return "SIGSEGV, a segmentation fault";
    case SIGBUS: return "SIGBUS, a bus error";
    case SIGFPE: return "SIGFPE, an arithmetic fault";
    case SIGILL: return "SIGILL, an illegal instruction";
    case SIGABRT: return "SIGABRT, abort()";
    case SIGKILL: return "SIGKILL; the system kills processes that use too much memory";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    default: return "a signal";
    }
}

// Virtual room for the arena: windows are sparse, so only what is written
// costs memory; a process-wide address-space limit makes them smaller.
uint64_t window_size()
{
    rlimit as{};
    uint64_t budget = uint64_t{2} << 40; // 2 TiB of addresses: windows of 32 GiB
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
        budget = std::min<uint64_t>(budget, as.rlim_cur / 4);
    uint64_t w = budget / kMaxChannels;
    w &= ~(uint64_t{2} * kMiB - 1);
    return std::clamp<uint64_t>(w, 64 * kMiB, 64 * kGiB);
}

} // namespace

PluginProcess::PluginProcess(const IsolationSettings &settings, const std::string &library_name)
    : settings_(settings), name_(library_name), channels_(kMaxChannels, false)
{
    window_bytes_ = window_size();
    arena_bytes_ = kArenaHeaderBytes + window_bytes_ * kMaxChannels;
    memfd_ = memfd_create("arbor-plugin-arena", MFD_CLOEXEC);
    if (memfd_ < 0)
        throw std::runtime_error(std::string("cannot create shared memory for an isolated plugin: ") +
                                 std::strerror(errno));
    if (ftruncate(memfd_, static_cast<off_t>(arena_bytes_)) != 0) {
        const int e = errno;
        close(memfd_);
        throw std::runtime_error(std::string("cannot size the shared memory of an isolated plugin: ") +
                                 std::strerror(e));
    }
    void *map = mmap(nullptr, arena_bytes_, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_NORESERVE, memfd_, 0);
    if (map == MAP_FAILED) {
        const int e = errno;
        close(memfd_);
        throw std::runtime_error(std::string("cannot map the shared memory of an isolated plugin: ") +
                                 std::strerror(e));
    }
    arena_ = static_cast<uint8_t *>(map);
    auto *arena = new (arena_) ArenaHeader{};
    arena->magic = kArenaMagic;
    arena->channels = kMaxChannels;
    arena->window_bytes = window_bytes_;
    channels_[0] = true;

    // The child's lifeline: it reads the other end and leaves when the host
    // is gone (every write end closed).  Not PR_SET_PDEATHSIG, which fires
    // when the spawning *thread* ends (a pipeline job restarting a plugin).
    int lifeline[2];
    if (pipe2(lifeline, O_CLOEXEC) != 0) {
        const int e = errno;
        munmap(arena_, arena_bytes_);
        close(memfd_);
        throw std::runtime_error(std::string("cannot create a pipe for an isolated plugin: ") + std::strerror(e));
    }
    lifeline_ = lifeline[1];
    const std::string helper = settings_.helper.string();
    const std::string bytes = std::to_string(arena_bytes_), limit = std::to_string(settings_.memory_limit);
    std::vector<char *> argv{const_cast<char *>(helper.c_str()), const_cast<char *>("--arena-fd"),
                             const_cast<char *>("3"),           const_cast<char *>("--arena-bytes"),
                             const_cast<char *>(bytes.c_str()), const_cast<char *>("--lifeline-fd"),
                             const_cast<char *>("4"),           const_cast<char *>("--memory-limit"),
                             const_cast<char *>(limit.c_str()), const_cast<char *>("--library"),
                             const_cast<char *>(name_.c_str()), nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, memfd_, 3); // dup2 clears close-on-exec
    posix_spawn_file_actions_adddup2(&actions, lifeline[0], 4);
    const int e = posix_spawn(&pid_, helper.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(lifeline[0]);
    if (e != 0) {
        close(lifeline_);
        munmap(arena_, arena_bytes_);
        close(memfd_);
        throw std::runtime_error("cannot start " + helper + " for an isolated plugin: " + std::strerror(e));
    }
}

PluginProcess::~PluginProcess()
{
    if (alive()) {
        // The library's deinit, then the child exits; a child that does not
        // is killed.
        const double timeout = settings_.timeout_seconds;
        settings_.timeout_seconds = std::min(timeout, 5.0);
        call(0, Op::Unload, 0, nullptr, nullptr);
    }
    if (!reap(false)) {
        for (int i = 0; i < 200 && !reap(false); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        if (!reap(false)) {
            kill(pid_, SIGKILL);
            reap(true);
        }
    }
    munmap(arena_, arena_bytes_);
    close(memfd_);
    close(lifeline_);
}

uint8_t *PluginProcess::window(uint32_t channel) const
{
    return arena_ + kArenaHeaderBytes + window_bytes_ * channel;
}

uint32_t PluginProcess::open_channel()
{
    std::lock_guard lock(mutex_);
    for (uint32_t c = 1; c < kMaxChannels; ++c)
        if (!channels_[c]) {
            channels_[c] = true;
            // A fresh header: sequence numbers from 0, an empty log.
            std::memset(window(c), 0, sizeof(ChannelHeader));
            return c;
        }
    return 0;
}

void PluginProcess::close_channel(uint32_t channel)
{
    std::lock_guard lock(mutex_);
    if (channel > 0 && channel < kMaxChannels)
        channels_[channel] = false;
    // What the instance's data took goes back to the system.
    fallocate(memfd_, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE,
              static_cast<off_t>(kArenaHeaderBytes + window_bytes_ * channel), static_cast<off_t>(window_bytes_));
}

void PluginProcess::release_bulk(uint32_t channel, uint64_t keep, uint64_t used)
{
    if (used <= keep + 64 * kMiB)
        return; // small calls keep their pages: the next call reuses them
    const uint64_t from = (kBulkAt + keep + 4095) & ~uint64_t{4095};
    fallocate(memfd_, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE,
              static_cast<off_t>(kArenaHeaderBytes + window_bytes_ * channel + from),
              static_cast<off_t>(window_bytes_ - from));
}

std::string PluginProcess::death() const
{
    std::lock_guard lock(mutex_);
    return death_;
}

void PluginProcess::mark_dead(const std::string &reason)
{
    std::lock_guard lock(mutex_);
    if (death_.empty())
        death_ = reason;
    dead_ = true;
}

// Collects the child's exit status once; true when it has ended.
bool PluginProcess::reap(bool wait)
{
    std::lock_guard lock(mutex_);
    if (reaped_)
        return true;
    int status = 0;
    const pid_t r = waitpid(pid_, &status, wait ? 0 : WNOHANG);
    if (r != pid_)
        return false;
    reaped_ = true;
    dead_ = true;
    if (death_.empty()) {
        if (WIFSIGNALED(status))
            death_ = std::string("crashed (") + describe_signal(WTERMSIG(status)) + ")";
        else
            death_ = "its process exited (status " + std::to_string(WEXITSTATUS(status)) + ")";
    }
    return true;
}

void PluginProcess::drain_log(uint32_t channel, const arbor_host *log)
{
    ChannelHeader &h = header(channel);
    uint64_t read = h.log_read.load(std::memory_order_relaxed);
    const uint64_t written = h.log_written.load(std::memory_order_acquire);
    if (written - read > kLogBytes) // a child that broke the ring: skip it
        read = written;
    auto byte = [&](uint64_t at) { return h.log[at % kLogBytes]; };
    while (written - read >= 8) {
        uint32_t level = 0, length = 0;
        for (int b = 0; b < 4; ++b) {
            level |= uint32_t(uint8_t(byte(read + b))) << (8 * b);
            length |= uint32_t(uint8_t(byte(read + 4 + b))) << (8 * b);
        }
        if (length > written - read - 8)
            break;
        std::string text(length, '\0');
        for (uint32_t i = 0; i < length; ++i)
            text[i] = byte(read + 8 + i);
        read += 8 + length;
        if (log && log->log)
            log->log(log, std::min<uint32_t>(level, ARBOR_LOG_ERROR), text.c_str());
    }
    h.log_read.store(read, std::memory_order_release);
    if (const uint32_t dropped = h.log_dropped.exchange(0); dropped && log && log->log)
        log->log(log, ARBOR_LOG_WARNING, (std::to_string(dropped) + " log messages dropped (too many at once)").c_str());
}

std::string PluginProcess::call(uint32_t channel, Op op, uint64_t request_size, arbor_task *task,
                                const arbor_host *log)
{
    if (!alive())
        return death();
    return wait(channel, post(channel, op, request_size), task, log);
}

uint32_t PluginProcess::post(uint32_t channel, Op op, uint64_t request_size)
{
    ChannelHeader &h = header(channel);
    h.op = static_cast<uint32_t>(op);
    h.request_size = request_size;
    h.reply_size = 0;
    h.cancel.store(0);
    const uint32_t before = h.reply.load(std::memory_order_acquire);
    h.request.store(before + 1, std::memory_order_release);
    futex_wake(h.request);
    return before;
}

std::string PluginProcess::wait(uint32_t channel, uint32_t before, arbor_task *task, const arbor_host *log)
{
    if (!alive())
        return death();
    ChannelHeader &h = header(channel);
    auto &arena = *reinterpret_cast<ArenaHeader *>(arena_);

    using clock = std::chrono::steady_clock;
    auto last_life = clock::now();
    uint32_t beat = h.heartbeat.load(std::memory_order_relaxed);
    uint32_t progress_seen = h.progress_seq.load(std::memory_order_acquire);
    const auto timeout = std::chrono::duration<double>(settings_.timeout_seconds);
    // Short calls (a simplifier's importance) are answered while we spin.
    if (!spin_until_changed(h.reply, before, 50'000)) {
        for (;;) {
            futex_wait(h.reply, before, 10);
            if (h.reply.load(std::memory_order_acquire) != before)
                break;
            if (arena.crash_signal.load() != 0 || reap(false)) {
                // The child is dying of a signal its handler announced.
                for (int i = 0; i < 200 && !reap(false); ++i)
                    std::this_thread::sleep_for(std::chrono::milliseconds(5));
                if (!reap(false)) {
                    kill(pid_, SIGKILL);
                    reap(true);
                }
                return death();
            }
            const uint32_t now_beat = h.heartbeat.load(std::memory_order_relaxed);
            if (now_beat != beat) {
                beat = now_beat;
                last_life = clock::now();
            }
            if (task) {
                const uint32_t p = h.progress_seq.load(std::memory_order_acquire);
                if (p != progress_seen && (p & 1) == 0) {
                    const double fraction = h.progress;
                    char stage[sizeof h.stage];
                    std::memcpy(stage, h.stage, sizeof stage);
                    stage[sizeof stage - 1] = '\0';
                    if (h.progress_seq.load(std::memory_order_acquire) == p) {
                        progress_seen = p;
                        task->progress(task, std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0,
                                       stage[0] ? stage : nullptr);
                    }
                }
                if (task->cancelled(task))
                    h.cancel.store(1, std::memory_order_release);
            }
            drain_log(channel, log);
            if (clock::now() - last_life > timeout) {
                char seconds[32];
                std::snprintf(seconds, sizeof seconds, "%g", settings_.timeout_seconds);
                mark_dead(std::string("did not answer for ") + seconds +
                          " s (no reply, no progress, no cancellation poll), so its process was stopped");
                kill(pid_, SIGKILL);
                reap(true);
                return death();
            }
        }
    }
    drain_log(channel, log);
    return "";
}

} // namespace arbor
