#include "plugin_call.hpp"

#include <pthread.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <mutex>
#include <new>

namespace arbor {

namespace {

// The call a thread is in.  Slots of threads that called plugins are shared
// so that a crash on another thread (a plugin's worker) can name them.
struct CallSlot {
    std::atomic<bool> taken{false};
    std::atomic<const char *> plugin{nullptr};
    std::atomic<const char *> function{nullptr};
};

constexpr int kSlots = 256;
CallSlot g_slots[kSlots];

// Constant-initialised and trivially destructible, so that the handler can
// read them without running any initialisation.
thread_local CallSlot *t_slot = nullptr;
thread_local CallSlot t_own_slot; // when every shared slot is taken

constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
struct sigaction g_previous[NSIG];

// What a thread set up on its first call; released when it exits.
struct ThreadState {
    CallSlot *slot = nullptr;
    void *stack = nullptr;
    std::size_t stack_size = 0;
};
pthread_key_t g_thread_key;

const char *signal_name(int signal)
{
    switch (signal) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT";
    default: return "a signal";
    }
}

// Appends `text` to the line being built (async-signal-safe: no library).
struct Line {
    char text[640];
    std::size_t length = 0;
    Line &operator<<(const char *s)
    {
        for (; s && *s && length < sizeof text - 1; ++s)
            text[length++] = *s;
        return *this;
    }
    void write_out()
    {
        text[length++] = '\n';
        for (std::size_t done = 0; done < length;) {
            const ssize_t n = ::write(STDERR_FILENO, text + done, length - done);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0)
                return;
            done += static_cast<std::size_t>(n);
        }
    }
};

void on_crash(int signal, siginfo_t *info, void *)
{
    const int saved_errno = errno;
    const CallSlot *mine = t_slot;
    if (const char *plugin = mine ? mine->plugin.load(std::memory_order_acquire) : nullptr) {
        Line line;
        line << "arbor: plugin " << plugin << " crashed (" << signal_name(signal) << ") in "
             << mine->function.load(std::memory_order_relaxed);
        line.write_out();
    } else {
        // A thread of a plugin's own, or of the host outside any call: name
        // the calls in progress, the likely culprits.
        int named = 0;
        for (const CallSlot &s : g_slots) {
            const char *plugin = s.plugin.load(std::memory_order_acquire);
            if (!plugin || named == 8)
                continue;
            Line line;
            line << "arbor: crashed (" << signal_name(signal) << ") on a thread outside the host's plugin calls while plugin "
                 << plugin << " was in " << s.function.load(std::memory_order_relaxed);
            line.write_out();
            ++named;
        }
    }
    // Let the signal take its course under the action that was there before:
    // a fault repeats when this returns; a signal sent (abort(), kill) is
    // sent again, and arrives once this handler returns.
    sigaction(signal, &g_previous[signal], nullptr);
    if (info->si_code <= 0)
        raise(signal);
    errno = saved_errno;
}

void release_thread(void *value)
{
    auto *state = static_cast<ThreadState *>(value);
    if (state->stack) {
        stack_t current{};
        if (sigaltstack(nullptr, &current) == 0 && current.ss_sp == state->stack) {
            stack_t off{};
            off.ss_flags = SS_DISABLE;
            sigaltstack(&off, nullptr);
        }
        munmap(state->stack, state->stack_size);
    }
    if (state->slot != &t_own_slot) {
        state->slot->plugin.store(nullptr);
        state->slot->function.store(nullptr);
        state->slot->taken.store(false, std::memory_order_release);
    }
    t_slot = nullptr;
    delete state;
}

void install_handlers()
{
    pthread_key_create(&g_thread_key, release_thread);
    for (const int signal : kSignals) {
        struct sigaction action{};
        action.sa_sigaction = on_crash;
        action.sa_flags = SA_SIGINFO | SA_ONSTACK;
        sigemptyset(&action.sa_mask);
        sigaction(signal, &action, &g_previous[signal]);
    }
}

// The first call on a thread: a slot, an alternate signal stack (unless the
// thread has one), the handlers (once per process).
CallSlot *enter_thread()
{
    static std::once_flag once;
    std::call_once(once, install_handlers);
    auto *state = new (std::nothrow) ThreadState;
    if (!state)
        return t_slot = &t_own_slot; // reported all the same, only not from other threads
    state->slot = &t_own_slot;
    for (CallSlot &s : g_slots) {
        bool expected = false;
        if (s.taken.compare_exchange_strong(expected, true, std::memory_order_acq_rel)) {
            state->slot = &s;
            break;
        }
    }
    stack_t current{};
    if (sigaltstack(nullptr, &current) == 0 && (current.ss_flags & SS_DISABLE)) {
        const std::size_t size = 64 * 1024 + static_cast<std::size_t>(MINSIGSTKSZ);
        void *stack = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (stack != MAP_FAILED) {
            stack_t alternate{};
            alternate.ss_sp = stack;
            alternate.ss_size = size;
            if (sigaltstack(&alternate, nullptr) == 0) {
                state->stack = stack;
                state->stack_size = size;
            } else {
                munmap(stack, size);
            }
        }
    }
    pthread_setspecific(g_thread_key, state);
    t_slot = state->slot;
    return t_slot;
}

} // namespace

PluginCall::PluginCall(const char *plugin, const char *function) noexcept
{
    CallSlot *slot = t_slot ? t_slot : enter_thread();
    outer_plugin_ = slot->plugin.load(std::memory_order_relaxed);
    outer_function_ = slot->function.load(std::memory_order_relaxed);
    slot->function.store(function, std::memory_order_relaxed);
    slot->plugin.store(plugin, std::memory_order_release);
}

PluginCall::~PluginCall()
{
    CallSlot *slot = t_slot;
    slot->plugin.store(outer_plugin_, std::memory_order_release);
    slot->function.store(outer_function_, std::memory_order_relaxed);
}

} // namespace arbor
