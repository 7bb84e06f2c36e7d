// data_file.hpp - a file opened for reading at arbor offsets, whose errors
// name it.  Every importer reads headers and voxel data through it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace arbor::importers {

class DataFile {
public:
    // Throws ARBOR_ERROR_IO when the file is missing, unreadable or not a
    // regular file.
    explicit DataFile(const std::filesystem::path &path);
    ~DataFile();
    DataFile(const DataFile &) = delete;
    DataFile &operator=(const DataFile &) = delete;

    const std::filesystem::path &path() const { return path_; }
    // The file name, for messages.
    const std::string &name() const { return name_; }
    uint64_t size() const { return size_; }

    // Reads up to `size` bytes at `offset`; fewer only at the end of the file
    // (0 at or past it).  Throws ARBOR_ERROR_IO on a read error.
    std::size_t read_at(uint64_t offset, void *dest, std::size_t size) const;

private:
    std::filesystem::path path_;
    std::string name_;
    int fd_ = -1;
    uint64_t size_ = 0;
};

} // namespace arbor::importers
