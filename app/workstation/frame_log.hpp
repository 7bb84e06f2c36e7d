// frame_log.hpp - `--frame-log PATH`: one line per UI frame, so a test (or a
// user reporting a stutter) sees how long each frame took and what was
// computing meanwhile:
//   time_s frame_ms jobs
//   12.034 16.7 contour_tree:0.42,render:0.00
// frame_ms is the frame's own time (input, drawing, swap), not the wait
// for the next event.
// ("-" when no job runs).  Written as it goes, flushed every frame.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace arbor::workstation {

class FrameLog {
public:
    FrameLog() = default;
    explicit FrameLog(const std::filesystem::path &path); // throws std::runtime_error
    ~FrameLog();
    FrameLog(const FrameLog &) = delete;
    FrameLog &operator=(const FrameLog &) = delete;

    bool open() const { return file_ != nullptr; }
    void write(double time_s, double frame_ms, const std::string &jobs);

private:
    std::FILE *file_ = nullptr;
};

} // namespace arbor::workstation
