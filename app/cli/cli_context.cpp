#include "cli_context.hpp"

#include <system_error>

namespace arbor::cli {

std::filesystem::path executable_path(const char *argv0)
{
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec)
        return self;
    return std::filesystem::absolute(argv0, ec);
}

} // namespace arbor::cli
