// workstation_window.hpp - `arbor view`: the GLFW window with Dear ImGui
// (OpenGL 3.3 core) drawing the workstation's state: the 3D view, the three
// slice views, the tree, the priority lines, the branch list, the controls,
// the relation wheel and the jobs, in a fixed layout that follows the
// window's size (ImGui 1.86 has no docking).  It never waits on work: the
// pipeline's jobs and the renders run on their own threads, and the loop
// polls for their results at least 30 times a second while they run.
#pragma once

#include <filesystem>
#include <optional>

namespace arbor::workstation {

class Workstation;

struct WindowOptions {
    std::optional<std::filesystem::path> open; // a volume, DICOM folder or session
    std::filesystem::path script;              // --script
    std::filesystem::path frame_log;           // --frame-log
    int width = 1600, height = 1000;
    bool recovery = true; // autosave and offer to restore after a crash
};

// Runs until the window closes or the script quits; the exit status (1 when
// the script failed, 2 when no window could be made).
int run_window(Workstation &workstation, const WindowOptions &options);

} // namespace arbor::workstation
