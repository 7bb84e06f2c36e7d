#include "atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <unistd.h>

namespace arbor {

namespace {

// Tells apart the temporary files of writers in one process: two threads
// writing the same target must not share (and truncate) one temporary file.
std::atomic<uint64_t> next_writer{0};

} // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target))
{
    // Created exclusively ("x"): a name left behind by a crashed process that
    // had our pid is skipped, never written through.
    for (int attempt = 0; attempt < 100; ++attempt) {
        temporary_ = target_;
        temporary_ += ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(next_writer++);
        file_ = std::fopen(temporary_.c_str(), "wbx");
        if (file_ || errno != EEXIST)
            break;
    }
    if (!file_)
        throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(errno));
}

AtomicFile::~AtomicFile()
{
    if (file_)
        std::fclose(file_);
    if (!committed_) {
        std::error_code ec;
        std::filesystem::remove(temporary_, ec);
    }
}

void AtomicFile::write(const void *data, std::size_t size)
{
    if (size && std::fwrite(data, 1, size, file_) != size)
        throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(errno));
}

void AtomicFile::commit()
{
    const bool flushed = std::fflush(file_) == 0;
    const int saved = errno;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!flushed || !closed)
        throw std::runtime_error("cannot write " + target_.string() + ": " +
                                 std::strerror(flushed ? errno : saved));
    std::error_code ec;
    std::filesystem::rename(temporary_, target_, ec);
    if (ec)
        throw std::runtime_error("cannot replace " + target_.string() + ": " + ec.message());
    committed_ = true;
}

} // namespace arbor
