#include "atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <unistd.h>

namespace arbor {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target))
{
    temporary_ = target_;
    temporary_ += ".partial-" + std::to_string(::getpid());
    file_ = std::fopen(temporary_.c_str(), "wb");
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
