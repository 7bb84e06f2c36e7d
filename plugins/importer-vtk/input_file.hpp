// input_file.hpp - checks on the input path before a VTK reader sees it.
//
// VTK reports a missing or unreadable file as a parse failure; checking
// first gives the host an I/O error with the system's reason instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace arbor::importer_vtk {

// The file name without its folder, for messages.
std::string file_name_of(const std::string &path);

// Whether the file name ends with `suffix` (lowercase, with the dot),
// ignoring case.
bool name_ends_with(const std::string &path, std::string_view suffix);

// Size in bytes of the regular file at `path`, which can be opened for
// reading.  Throws ARBOR_ERROR_IO (missing, a folder, no permission) or
// ARBOR_ERROR_FORMAT (empty file).
uint64_t require_readable_file(const std::string &path);

// Up to `max_bytes` from the start of the file ("" when it cannot be read).
std::string read_file_start(const std::string &path, std::size_t max_bytes);

} // namespace arbor::importer_vtk
