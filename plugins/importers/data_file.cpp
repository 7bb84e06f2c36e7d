// data_file.cpp - see data_file.hpp.  POSIX pread keeps reads positioned
// without a shared seek pointer.
#include "data_file.hpp"

#include <arbor/sdk/error.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <sys/stat.h>
#include <unistd.h>

namespace arbor::importers {

DataFile::DataFile(const std::filesystem::path &path) : path_(path), name_(path.filename().string())
{
    // O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused below).
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd_ < 0) {
        const int error = errno;
        if (error == ENOENT)
            sdk::fail(ARBOR_ERROR_IO, path.string() + " does not exist");
        sdk::fail(ARBOR_ERROR_IO, "cannot open " + path.string() + ": " + std::strerror(error));
    }
    struct stat info {};
    if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        sdk::fail(ARBOR_ERROR_IO, path.string() + " is not a regular file");
    }
    size_ = static_cast<uint64_t>(info.st_size);
}

DataFile::~DataFile()
{
    if (fd_ >= 0)
        ::close(fd_);
}

std::size_t DataFile::read_at(uint64_t offset, void *dest, std::size_t size) const
{
    std::size_t done = 0;
    auto *out = static_cast<unsigned char *>(dest);
    while (done < size && offset + done < size_) {
        const uint64_t at = offset + done;
        if (at > static_cast<uint64_t>(std::numeric_limits<off_t>::max()))
            break;
        const std::size_t want = std::min<std::size_t>(size - done, std::size_t{1} << 30);
        const ssize_t got = ::pread(fd_, out + done, want, static_cast<off_t>(at));
        if (got < 0) {
            if (errno == EINTR)
                continue;
            sdk::fail(ARBOR_ERROR_IO, "cannot read " + name_ + ": " + std::strerror(errno));
        }
        if (got == 0)
            break;
        done += static_cast<std::size_t>(got);
    }
    return done;
}

} // namespace arbor::importers
