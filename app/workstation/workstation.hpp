// workstation.hpp - the workstation's state without its window: the
// pipeline and the progressive 3D view on it, the undo history of the
// user's choices, and the view state the panels share (crosshair, window,
// overlay, hover).  Every action a person's click or a script line causes is
// a member function here, so the panels, the script runner and the tests
// all drive the same code; the window (workstation_window.hpp) only draws
// this state and turns input into these calls.
//
// Threading: every member is called from the UI thread; the pipeline's jobs
// and the progressive view's renders run on their own threads and are read
// here as snapshots.
#pragma once

#include "history.hpp"
#include "window_level.hpp"

#include "pipeline/pipeline.hpp"
#include "pipeline/progressive_view.hpp"

#include <array>
#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace arbor::workstation {

struct ViewState {
    std::array<int64_t, 3> crosshair{0, 0, 0}; // voxel (i, j, k) the slice views show
    WindowLevel window;
    std::string window_preset = "auto"; // or a CT preset's name, or "manual"
    double overlay_opacity = 0.35;
    bool overlay = true;
    std::optional<uint32_t> hovered; // the branch under the mouse in any view
    bool help = false;               // the help overlay is shown
};

struct Message {
    arbor_log_level level = ARBOR_LOG_INFO;
    std::string text;
};

class Workstation {
public:
    Workstation(const PluginRegistry &registry, pipeline::PipelineOptions options);
    ~Workstation();
    Workstation(const Workstation &) = delete;
    Workstation &operator=(const Workstation &) = delete;

    pipeline::Pipeline &pipeline() { return pipeline_; }
    const pipeline::PluginCatalog &catalog() const { return pipeline_.catalog(); }
    pipeline::ProgressiveView &volume_view() { return *view3d_; }
    // The 3D view's frames, from renderers that draw into OpenGL, drawn on
    // this surface's canvas (nullptr: as images).  Restarts the view's
    // thread (set on_frame again after).
    // `read_back` reads a frame drawn there (for screenshots; on the
    // thread that calls screenshot, with a context that sees the texture).
    void draw_on(std::shared_ptr<pipeline::FrameSurface> surface,
                 std::function<RenderedImage(const GlFrame &)> read_back = {});
    const History &history() const { return history_; }
    ViewState &view() { return view_; }
    const pipeline::Document &document() const { return history_.current(); }

    // Opens a volume file, a DICOM file or folder, or an arbor-session/1
    // file (by its content); throws std::invalid_argument / SessionError
    // with the reason, the current document staying as it was.
    void open(const std::filesystem::path &path);
    void open_document(const pipeline::Document &document, const std::string &what);
    bool has_input() const { return !history_.current().input.empty(); }
    // The file or folder open now ("" for none; "phantom:head").
    std::string input_name() const;

    // A change of the document: checked by the pipeline (std::invalid_argument,
    // nothing changes), shown at once (a coarse frame), recorded as an undo step
    // unless `commit` is false (a slider being dragged; commit() ends it).
    void change(const pipeline::Document &document, const std::string &what, bool commit = true);
    void commit(const std::string &what);
    // `set NAME VALUE` (controls.hpp).
    void set(const std::string &name, const std::string &value, bool commit = true);
    bool undo();
    bool redo();

    // Selection, shared by every view (-1 or nullopt: none).
    void select(std::optional<int32_t> label);
    // The priority line's threshold at `fraction` of its row's height: the
    // kept branches are those whose importance exceeds fraction x the most
    // important non-root branch's.
    void drag_threshold(double fraction, bool commit = true);
    // A person's edit of one kept branch's look (pipeline BranchStyle): it
    // follows the structure through new cuts until reset.  Throws
    // std::invalid_argument for a label the simplified tree does not have.
    pipeline::BranchStyle branch_style(uint32_t label) const;
    void set_branch_style(uint32_t label, const pipeline::BranchStyle &style, bool commit = true);
    void reset_branch_styles();
    // Per label of the current cut: hidden by its style (the slice overlay
    // leaves it out too).
    std::vector<bool> hidden_labels() const;

    // Absolute orbit angles (degrees); `rotate` adds to them.
    void orbit(double azimuth, double elevation, bool commit = true);
    void rotate(double d_azimuth, double d_elevation, bool commit = false);
    void zoom_by(double factor, bool commit = false);
    void pan_by(double dx_mm, double dy_mm, bool commit = false);
    // One of the six standard views: "anterior", "posterior", "left",
    // "right", "superior", "inferior"; "reset" for the default.
    void standard_view(const std::string &name);
    void window_level(double width, double level);
    void window_preset(const std::string &name); // a CT preset, or "auto"
    void move_crosshair(const std::array<int64_t, 3> &ijk);
    // The crosshair to the first opaque point under pixel (x, y) of the 3D
    // view's latest frame, and the branch there selected (but the root);
    // false when the ray hit nothing.
    bool pick(double x, double y);

    // The 3D view's size in pixels (the viewport); not an undo step.
    void set_viewport(uint32_t width, uint32_t height);
    std::array<uint32_t, 2> viewport() const { return viewport_; }

    void save_session(const std::filesystem::path &path);
    // The 3D view as the pipeline renders it (PNG or EXR by suffix): the
    // render stage's frame, the same `arbor run --session` gives; throws
    // when there is none yet.
    void screenshot(const std::filesystem::path &path);
    // Label map (NRRD with a Slicer colour table) and transfer functions
    // (arbor-transfer-functions/1) of what is shown.
    // Exports are written on a thread of their own (a label map of a CT is
    // hundreds of milliseconds of compression): the window keeps drawing,
    // the message comes when the file is written, idle() waits for them and
    // a failure becomes error().
    void export_labels(const std::filesystem::path &path);
    void export_transfer_functions(const std::filesystem::path &path);
    // Waits for the exports still being written; their failures.
    std::vector<std::string> finish_writes();

    // Cancel: every job and the render in flight stop; nothing is asked
    // again until resume() or the next change (the Jobs panel offers Resume).
    void cancel();
    void resume();
    bool cancelled() const { return cancelled_; }

    // Once per UI frame: requests what the views need, picks up new results.
    void poll();
    // Every job done and the 3D view showing the pipeline's current frame.
    bool idle() const;
    // Stages being computed, for the frame log and the job panel.
    std::vector<std::shared_ptr<pipeline::Job>> jobs() const { return pipeline_.active_jobs(); }

    // Messages for the status bar and the log panel (newest last).
    const std::deque<Message> &messages() const { return messages_; }
    void say(arbor_log_level level, const std::string &text);
    // The latest failure of a job or the 3D view ("" when none).
    std::string error() const { return error_; }

    // Per label its colour (branch_colors.hpp) in the latest transfer
    // functions; empty before there are any.
    const std::vector<std::array<float, 3>> &colors();
    // Per label its share of the 3D view's visibility (empty when the
    // renderer does not measure it).
    std::vector<double> visibility_shares() const;


private:
    pipeline::Document for_pipeline(pipeline::Document d) const;
    void show(const pipeline::Document &document); // set on the pipeline, touch the view
    void volume_changed();
    void request_views();
    void harvest_writes(bool wait);

    pipeline::Pipeline pipeline_;
    std::unique_ptr<pipeline::ProgressiveView> view3d_;
    std::function<RenderedImage(const GlFrame &)> read_back_;
    History history_;
    ViewState view_;
    std::array<uint32_t, 2> viewport_{512, 512};
    uint64_t touch_ = 0;
    uint64_t filter_revision_ = 0; // of the volume the view state was set for
    std::deque<Message> messages_;
    std::string error_;
    std::vector<std::future<std::string>> writes_; // exports being written; each says what it wrote
    std::vector<std::string> write_failures_;
    bool cancelled_ = false;
    std::array<uint64_t, pipeline::kGroupCount> requested_{};
    std::vector<std::array<float, 3>> colors_;
    const void *colors_of_ = nullptr; // the transfer functions colors_ are of // the revisions poll() last asked for
};

} // namespace arbor::workstation
