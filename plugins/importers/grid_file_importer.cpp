// grid_file_importer.cpp - see grid_file_importer.hpp.
#include "grid_file_importer.hpp"

#include "text_scan.hpp"

#include <system_error>

namespace arbor::importers {

std::filesystem::path resolve_data_file(const std::filesystem::path &header_path,
                                        const std::string &named, const std::string &header_name)
{
    const std::filesystem::path given(named);
    const std::filesystem::path file = given.is_absolute() ? given : header_path.parent_path() / given;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        sdk::fail(ARBOR_ERROR_IO, "data file " + excerpt(named) + " named in the header of " +
                                      header_name +
                                      (std::filesystem::exists(file, ec) ? " is not a regular file"
                                                                         : " does not exist") +
                                      " (looked for " + file.string() + ")");
    return file;
}

} // namespace arbor::importers
