#include "isolation_wire.hpp"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <ctime>

namespace arbor::isolation {

const char *op_call_name(Op op)
{
    switch (op) {
    case Op::Load: return "entry.init";
    case Op::Create: return "entry.create_plugin";
    case Op::Destroy: return "plugin.destroy";
    case Op::Unload: return "entry.deinit";
    case Op::ParamGet: return "params.get";
    case Op::ParamSet: return "params.set";
    case Op::Probe: return "importer.probe";
    case Op::ReadHeader: return "importer.read_header";
    case Op::ReadVoxels: return "importer.read_voxels";
    case Op::OutputType: return "filter.output_type";
    case Op::Apply: return "filter.apply";
    case Op::Prepare: return "simplifier.prepare";
    case Op::Importance: return "simplifier.importance";
    case Op::Depict: return "depictor.depict";
    case Op::Related: return "depictor.related";
    case Op::Legend: return "depictor.legend";
    case Op::Generate: return "tf_generator.generate";
    case Op::Render1: return "renderer.render";
    case Op::Render2: return "renderer.render";
    case Op::DescribeDevice: return "render_device.describe";
    }
    return "a call";
}

void MessageWriter::put_raw(const void *data, uint64_t size)
{
    if (size > capacity_ - size_)
        throw WireError("the message does not fit its area (" + std::to_string(capacity_ >> 20) + " MiB)");
    if (size)
        std::memcpy(base_ + size_, data, size);
    size_ += size;
}

void MessageWriter::put_string(const char *text, uint64_t max_length)
{
    if (!text) {
        put<uint32_t>(UINT32_MAX);
        return;
    }
    const uint64_t n = strnlen(text, max_length);
    put<uint32_t>(static_cast<uint32_t>(n));
    put_raw(text, n);
}

void MessageWriter::put_string(std::string_view text)
{
    const uint64_t n = std::min<uint64_t>(text.size(), UINT32_MAX - 1);
    put<uint32_t>(static_cast<uint32_t>(n));
    put_raw(text.data(), n);
}

void MessageWriter::put_sized(const void *data, uint64_t size)
{
    put<uint64_t>(size);
    put_raw(data, size);
}

void MessageReader::get_raw(void *out, uint64_t size)
{
    if (size > size_ - at_)
        throw WireError("a message ends early");
    std::memcpy(out, base_ + at_, size);
    at_ += size;
}

std::string MessageReader::get_string(bool *null)
{
    const uint32_t n = get<uint32_t>();
    if (null)
        *null = n == UINT32_MAX;
    if (n == UINT32_MAX)
        return {};
    if (n > size_ - at_)
        throw WireError("a string runs past its message");
    std::string s(reinterpret_cast<const char *>(base_ + at_), n);
    at_ += n;
    return s;
}

std::string MessageReader::get_sized()
{
    const uint64_t n = get<uint64_t>();
    if (n > size_ - at_)
        throw WireError("a block runs past its message");
    std::string s(reinterpret_cast<const char *>(base_ + at_), n);
    at_ += n;
    return s;
}

void futex_wake(std::atomic<uint32_t> &word)
{
    syscall(SYS_futex, reinterpret_cast<uint32_t *>(&word), FUTEX_WAKE, INT_MAX, nullptr, nullptr, 0);
}

void futex_wait(std::atomic<uint32_t> &word, uint32_t value, int timeout_ms)
{
    timespec ts{timeout_ms / 1000, (timeout_ms % 1000) * 1000000L};
    syscall(SYS_futex, reinterpret_cast<uint32_t *>(&word), FUTEX_WAIT, value, timeout_ms < 0 ? nullptr : &ts,
            nullptr, 0);
}

bool spin_until_changed(const std::atomic<uint32_t> &word, uint32_t value, int64_t spin_ns)
{
    const auto until = std::chrono::steady_clock::now() + std::chrono::nanoseconds(spin_ns);
    for (int i = 0;; ++i) {
        if (word.load(std::memory_order_acquire) != value)
            return true;
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
        if ((i & 63) == 63 && std::chrono::steady_clock::now() >= until)
            return word.load(std::memory_order_acquire) != value;
    }
}

} // namespace arbor::isolation
