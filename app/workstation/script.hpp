// script.hpp - `arbor view --script steps.txt`: one command per line, run as
// if a person did it, one step per UI frame, so the window keeps drawing
// while a script runs (and a test sees the frames a person would).
//
//   open PATH                  a volume, DICOM folder or session
//   wait idle [SECONDS]        until every job is done and the 3D view current (default 600 s)
//   expect-error TEXT          until the work fails with a message containing TEXT
//                              (one word; for tests of failures; at most 600 s)
//   set NAME VALUE             any control (controls.hpp): set flow-rate 150, set keep 12
//   select LABEL | none        the selection every view shares
//   drag-threshold FRACTION    the priority line's threshold at that height
//   orbit AZIMUTH ELEVATION    degrees
//   view NAME                  anterior, posterior, left, right, superior, inferior, reset
//   window-level W L           the slice views' window
//   window-preset NAME         brain, bone, lung, soft-tissue, abdomen, auto
//   pick X Y                   click the 3D view at frame pixel (X, Y)
//   hide LABEL | show LABEL    a kept branch in the 3D view and the slices
//   branch-opacity LABEL X     its optical depth times X
//   reset-styles               every branch as the transfer functions have it
//   undo | redo
//   screenshot PATH            the 3D view (PNG or EXR)
//   screenshot-window PATH     the whole window (PNG)
//   save-session PATH
//   export-labels PATH | export-tf PATH
//   pacs-search NODE [patient=P] [study-date=D] [modality=M] [accession=A]
//                              the DICOM browser's PACS tab searches series
//                              (`wait idle` waits for the answer)
//   pacs-open ROW              opens row ROW (1-based) of that search
//   quit
//
// Blank lines and lines starting with '#' are skipped.  The whole script is
// checked before it runs: an unknown command or a wrong argument count
// names its line.  A step that fails stops the script with its line number.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace arbor::workstation {

class Workstation;

struct ScriptLine {
    std::size_t number = 0; // 1-based, in the file
    std::string command;
    std::vector<std::string> args;
};

class ScriptError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws ScriptError("steps.txt:3: unknown command 'fly'").
std::vector<ScriptLine> parse_script(const std::string &text, const std::string &name);

// What only the window can do for a script.
class ScriptWindow {
public:
    virtual ~ScriptWindow() = default;
    // Write the whole window (as drawn this frame) to a PNG.
    virtual void capture_window(const std::filesystem::path &path) = 0;
    virtual void quit() = 0;
    // Work of the window's own that `wait idle` waits for (a DICOM folder
    // scan, a PACS search).
    virtual bool busy() const { return false; }
    // The PACS tab: search (filters "key=value"), open a row of the result.
    virtual void pacs_search(const std::string &node, const std::vector<std::string> &filters) = 0;
    virtual void pacs_open(std::size_t row) = 0;
};

class ScriptRunner {
public:
    ScriptRunner(std::vector<ScriptLine> lines, std::string name) : lines_(std::move(lines)), name_(std::move(name)) {}
    // Runs the next step when it can (a `wait` waits); false once the
    // script has ended.  Throws ScriptError naming the line of a failed step.
    bool step(Workstation &workstation, ScriptWindow &window);
    bool done() const { return next_ >= lines_.size(); }
    // The line being run or waited on ("" when done).
    std::string current() const;

private:
    void run(const ScriptLine &line, Workstation &workstation, ScriptWindow &window);

    std::vector<ScriptLine> lines_;
    std::string name_;
    std::size_t next_ = 0;
    std::optional<std::chrono::steady_clock::time_point> waiting_since_;
};

} // namespace arbor::workstation
