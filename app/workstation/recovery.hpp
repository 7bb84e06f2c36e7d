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

// Most recent first, at most 10; entries that no longer exist are dropped.
std::vector<std::filesystem::path> recent_files();
void add_recent_file(const std::filesystem::path &path);

} // namespace arbor::workstation
