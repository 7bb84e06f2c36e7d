// frame_log.hpp - `--frame-log PATH`: one line per UI frame, so a test (or a
// user reporting a stutter) sees how long each frame took and what was
// computing meanwhile:
//   time_s frame_ms jobs
//   12.034 16.7 contour_tree:0.42,render:0.00
// frame_ms is the frame's own time (input, drawing, swap), not the wait
// for the next event.
// ("-" when no job runs).  A frame over the UI's budget (33 ms: 30 frames
// a second) also says where its
// time went: the UI thread's CPU time and page faults in the frame, and the
// milliseconds of each phase (script step, poll, views, GL, swap...):
//   12.340 281.0 contour_tree:1.00 [cpu 12.1 faults 3 | script 0.0 poll 0.1 views 270.2 gl 8.0 swap 2.1]
// CPU time far below the frame's says the thread waited (a lock, the
// scheduler), not computed.  Written as it goes, flushed every frame.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace arbor::workstation {

// Frames at least this long say where their time went.
constexpr double kExplained = 33.0;

class FrameLog {
public:
    FrameLog() = default;
    explicit FrameLog(const std::filesystem::path &path); // throws std::runtime_error
    ~FrameLog();
    FrameLog(const FrameLog &) = delete;
    FrameLog &operator=(const FrameLog &) = delete;

    bool open() const { return file_ != nullptr; }
    // `where`: the breakdown, written only for slow frames.
    void write(double time_s, double frame_ms, const std::string &jobs, const std::string &where = "");

private:
    std::FILE *file_ = nullptr;
};

} // namespace arbor::workstation
