// input_file.cpp - existence, readability and size of an input file.
#include "input_file.hpp"

#include <arbor/sdk/error.hpp>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <system_error>
#include <filesystem>
#include <fstream>

namespace arbor::importer_vtk {

namespace fs = std::filesystem;

std::string file_name_of(const std::string &path)
{
    const std::string name = fs::path(path).filename().string();
    return name.empty() ? path : name;
}

bool name_ends_with(const std::string &path, std::string_view suffix)
{
    std::string name = file_name_of(path);
    if (name.size() < suffix.size())
        return false;
    for (char &c : name)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

uint64_t require_readable_file(const std::string &path)
{
    const std::string name = file_name_of(path);
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec && ec != std::errc::no_such_file_or_directory)
        sdk::fail(ARBOR_ERROR_IO, name + ": cannot be examined (" + ec.message() + ")");
    if (!fs::exists(status))
        sdk::fail(ARBOR_ERROR_IO, name + ": no such file (" + path + ")");
    if (fs::is_directory(status))
        sdk::fail(ARBOR_ERROR_IO, name + ": is a folder, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        sdk::fail(ARBOR_ERROR_IO, name + ": cannot be opened for reading (" +
                                      std::strerror(errno) + ")");
    const uint64_t size = fs::file_size(path, ec);
    if (ec)
        sdk::fail(ARBOR_ERROR_IO, name + ": cannot tell its size (" + ec.message() + ")");
    if (size == 0)
        sdk::fail(ARBOR_ERROR_FORMAT, name + ": the file is empty");
    return size;
}

std::string read_file_start(const std::string &path, std::size_t max_bytes)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return "";
    std::string bytes(max_bytes, '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    return bytes;
}

} // namespace arbor::importer_vtk
