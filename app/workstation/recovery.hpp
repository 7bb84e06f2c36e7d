// recovery.hpp - what survives a crash: the session autosaved (atomically,
// at most every two seconds while it changes) to a recovery file, removed
// when the workstation quits normally; found at the next start, it is
// offered for restoring.  Also the recent-files list.  Both live in
// $XDG_STATE_HOME/arbor (~/.local/state/arbor), or where ARBOR_STATE_DIR says.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace arbor::workstation {

std::filesystem::path state_folder();
std::filesystem::path recovery_path();

class Workstation;

// The autosave: tick() once a frame writes the session to recovery_path()
// when the document changed and two seconds passed since the last write;
// finish() removes the file (a normal end).  Failures are told once a
// minute, never thrown: an autosave must not stop the work.
class Autosave {
public:
    explicit Autosave(std::filesystem::path path = recovery_path()) : path_(std::move(path)) {}
    void tick(Workstation &workstation, double now_seconds);
    void finish();
    const std::filesystem::path &path() const { return path_; }

private:
    std::filesystem::path path_;
    double last_ = -1e9;
    std::string saved_; // the session text last written
};

// Most recent first, at most 10; entries that no longer exist are dropped.
std::vector<std::filesystem::path> recent_files();
void add_recent_file(const std::filesystem::path &path);

} // namespace arbor::workstation
