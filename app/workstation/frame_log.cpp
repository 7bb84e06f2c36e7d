#include "frame_log.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace arbor::workstation {

FrameLog::FrameLog(const std::filesystem::path &path) : file_(std::fopen(path.c_str(), "w"))
{
    if (!file_)
        throw std::runtime_error(path.string() + ": cannot write the frame log: " + std::strerror(errno));
    std::fprintf(file_, "time_s frame_ms jobs\n");
}

FrameLog::~FrameLog()
{
    if (file_)
        std::fclose(file_);
}

void FrameLog::write(double time_s, double frame_ms, const std::string &jobs, const std::string &where)
{
    if (!file_)
        return;
    std::fprintf(file_, "%.3f %.1f %s%s\n", time_s, frame_ms, jobs.empty() ? "-" : jobs.c_str(),
                 where.empty() || frame_ms < kExplained ? "" : (" [" + where + "]").c_str());
    std::fflush(file_);
}

} // namespace arbor::workstation
