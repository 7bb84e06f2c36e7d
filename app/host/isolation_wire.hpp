// isolation_wire.hpp - what the host and an isolated plugin's process
// (`arbor-plugin-host`) share: one memfd arena, mapped by both, cut into
// windows, one per channel.  Channel 0 talks about the library (load,
// create, destroy); every plugin instance gets a channel of its own, so calls
// into different instances run at the same time as they do in-process.
//
// A window is
//
//   [0, 64 KiB)        the channel's header: the call's sequence numbers
//                      (futex words), cancellation, heartbeat, progress, log
//   [64 KiB, 8 MiB)    the request message (host writes, child reads)
//   [8 MiB, 16 MiB)    the reply message (child writes, host reads)
//   [16 MiB, window)   bulk data: volumes, label maps, images, lookup
//                      tables, placed by the host at offsets it names in the
//                      request; the child's task->allocate takes from the top
//
// The arena is a sparse memfd: only what is written takes memory, and the
// host punches out what a call used once it copied the results.  Big inputs
// are copied into the window once (a renderer's volume and labels once per
// revision), outputs copied out once.
//
// A call: the host writes the request, bumps `request` and wakes the child's
// channel thread (futex); the child answers into the reply area, sets
// `reply` to the request's number and wakes the host.  Both spin briefly
// before sleeping, so the hundreds of thousands of small calls of a
// simplifier cost about a microsecond each.  Nothing the child wrote is
// trusted: every offset and length is checked before the host reads it.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace arbor::isolation {

constexpr uint64_t kKiB = 1024, kMiB = 1024 * kKiB, kGiB = 1024 * kMiB;
constexpr uint64_t kRequestAt = 64 * kKiB, kRequestBytes = 8 * kMiB - kRequestAt;
constexpr uint64_t kReplyAt = 8 * kMiB, kReplyBytes = 8 * kMiB;
constexpr uint64_t kBulkAt = 16 * kMiB;
constexpr uint64_t kArenaHeaderBytes = 2 * kMiB; // before window 0
constexpr uint32_t kMaxChannels = 64;            // channel 0 + 63 live instances per library
constexpr uint64_t kLogBytes = 32 * kKiB;

// What the requests ask.
enum class Op : uint32_t {
    Load = 1,   // channel 0: load the library, describe its plugins
    Create,     // channel 0: create an instance with its own channel
    Destroy,    // channel 0: destroy an instance, end its channel
    Unload,     // channel 0: deinit the library and exit
    ParamGet,
    ParamSet,
    Probe,
    ReadHeader,
    ReadVoxels,
    OutputType,
    Apply,
    Prepare,
    Importance,
    Depict,
    Related,
    Legend,
    Generate,
    Render1,
    Render2,
    DescribeDevice,
};
const char *op_call_name(Op op); // "filter.apply"

// The process's shared state, at the arena's start.
struct ArenaHeader {
    uint32_t magic;
    uint32_t channels;
    uint64_t window_bytes;
    // The child's fatal signal, written by its handler before it wakes every
    // waiting host thread: the host learns of a crash at once instead of at
    // its next poll.
    std::atomic<int32_t> crash_signal;
};
constexpr uint32_t kArenaMagic = 0x41524231; // "ARB1"

// The header of one channel's window.
struct ChannelHeader {
    std::atomic<uint32_t> request;   // host: the number of the posted call
    std::atomic<uint32_t> reply;     // child: the number of the answered call
    std::atomic<uint32_t> cancel;    // host: 1 while the call's task is cancelled
    std::atomic<uint32_t> heartbeat; // child: +1 at every progress or cancellation poll
    std::atomic<uint32_t> progress_seq; // odd while the child writes progress
    uint32_t op;
    uint64_t request_size;
    uint64_t reply_size;
    double progress;
    char stage[120];
    // task->allocate: the child takes [allocate_top, allocate_limit) from
    // the top of bulk, growing down (host-placed data grows up).
    std::atomic<uint64_t> allocate_top;
    uint64_t allocate_limit;
    // Log messages of the channel's instance (library for channel 0):
    // records of u32 level, u32 length, text, written by the child under
    // its own lock, read by the host.
    std::atomic<uint64_t> log_written;
    std::atomic<uint64_t> log_read;
    std::atomic<uint32_t> log_dropped;
    char log[kLogBytes];
};
static_assert(sizeof(ChannelHeader) <= kRequestAt);
static_assert(std::atomic<uint32_t>::is_always_lock_free && std::atomic<uint64_t>::is_always_lock_free);

class WireError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Appends values to a message area.
class MessageWriter {
public:
    MessageWriter(uint8_t *base, uint64_t capacity) : base_(base), capacity_(capacity) {}
    template <class T>
    void put(const T &value)
    {
        static_assert(std::is_trivially_copyable_v<T>);
        put_raw(&value, sizeof value);
    }
    // u32 length then the bytes; UINT32_MAX for NULL.
    void put_string(const char *text, uint64_t max_length = 1 << 20);
    void put_string(std::string_view text);
    void put_sized(const void *data, uint64_t size); // u64 size then bytes
    uint64_t size() const { return size_; }

private:
    void put_raw(const void *data, uint64_t size);
    uint8_t *base_;
    uint64_t capacity_, size_ = 0;
};

// Reads a message back in the order it was written; throws WireError when
// it runs past the end.  Reads copy: the other side may still be writing.
class MessageReader {
public:
    MessageReader(const uint8_t *base, uint64_t size) : base_(base), size_(size) {}
    template <class T>
    T get()
    {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        get_raw(&value, sizeof value);
        return value;
    }
    // A string put with put_string; `null` set when it was NULL.
    std::string get_string(bool *null = nullptr);
    // A sized blob: its bytes, copied.
    std::string get_sized();

private:
    void get_raw(void *out, uint64_t size);
    const uint8_t *base_;
    uint64_t size_, at_ = 0;
};

// Futex wait/wake on a word shared between processes.
void futex_wake(std::atomic<uint32_t> &word);
// Sleeps while word == value, at most timeout_ms (negative: no limit).
void futex_wait(std::atomic<uint32_t> &word, uint32_t value, int timeout_ms);

// Spins about `spin_ns`, then returns whether word != value.
bool spin_until_changed(const std::atomic<uint32_t> &word, uint32_t value, int64_t spin_ns);

} // namespace arbor::isolation
