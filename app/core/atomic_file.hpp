// atomic_file.hpp - write a file so that readers never see a half-written one
// and an existing file survives a failed write: data goes to a temporary file
// in the same folder, which replaces the target only after a successful close.
// Each writer has its own temporary file, so threads or processes writing the
// same target at once each replace it with a whole file.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace arbor {

class AtomicFile {
public:
    // Opens a temporary file next to `target`; throws std::runtime_error with
    // the reason when the folder is not writable.
    explicit AtomicFile(std::filesystem::path target);
    ~AtomicFile(); // removes the temporary file unless commit() succeeded
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    std::FILE *stream() { return file_; }
    void write(const void *data, std::size_t size);
    void write(const std::string &text) { write(text.data(), text.size()); }
    // Flushes, closes and renames onto the target; throws on failure.
    void commit();

private:
    std::filesystem::path target_, temporary_;
    std::FILE *file_ = nullptr;
    bool committed_ = false;
};

} // namespace arbor
