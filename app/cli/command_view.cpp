// `arbor view [volume | DICOM folder | session.json]`: the workstation, a
// thin front on the same pipeline as every other command
// (workstation/workstation_window.hpp).  --script runs a file of steps as
// if a person did them (workstation/script.hpp); --frame-log writes a line
// per UI frame.
#include "commands.hpp"
#include "pacs_fetch.hpp"

#include "pipeline/tree_cache.hpp"
#include "workstation/workstation.hpp"
#include "workstation/workstation_window.hpp"

#include "io/phantom.hpp"

#include <cstdio>
#include <sys/prctl.h>

namespace arbor::cli {

namespace {

struct ViewArgs {
    std::string input, phantom, script, frame_log;
    int width = 1600, height = 1000;
    bool no_recovery = false, no_cache = false;
};

int run_view(Context &context, const ViewArgs &a)
{
    // No transparent huge pages in an interactive session: faulting them in
    // compacts memory while the process' memory map is locked, and the UI
    // thread's next allocation waited up to 0.4 s behind a job's (measured on
    // the CT head: frames of 420 ms while the contour tree was computed; none
    // over 100 ms without, and the whole session 20 % faster).  The batch
    // commands keep them.
    prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);
    pipeline::PipelineOptions o;
    o.max_volume_bytes = context.max_volume_bytes;
    o.fetch_input = fetch_pacs_input;
    if (!a.no_cache) {
        try {
            o.tree_cache_folder = pipeline::TreeCache::default_folder();
            o.tree_cache_max_bytes = pipeline::TreeCache::default_max_bytes();
        } catch (const std::exception &e) {
            o.tree_cache_folder.clear();
        }
    }
    workstation::Workstation ws(context.registry, o);
    workstation::WindowOptions w;
    w.width = a.width;
    w.height = a.height;
    w.script = a.script;
    w.frame_log = a.frame_log;
    // A scripted run is a test or a batch job: it neither leaves nor offers a recovery file.
    w.recovery = !a.no_recovery && a.script.empty();
    if (!a.input.empty()) {
        if (!std::filesystem::exists(a.input)) {
            std::fprintf(stderr, "arbor view: %s: no such file or folder\n", a.input.c_str());
            return 1;
        }
        w.open = a.input;
    } else if (!a.phantom.empty()) {
        pipeline::Document d = ws.document();
        d.input = {};
        d.input.phantom = pipeline::PhantomInput{a.phantom};
        ws.open_document(d, "open the " + a.phantom + " phantom");
    }
    return workstation::run_window(ws, w);
}

} // namespace

void add_view_command(CLI::App &app, Context &context)
{
    auto args = std::make_shared<ViewArgs>();
    CLI::App *sub = app.add_subcommand("view", "The workstation: 3D view, slice views, tree, priority lines, branches");
    sub->add_option("input", args->input, "Volume file, DICOM folder or arbor session (.json) to open");
    sub->add_option("--phantom", args->phantom, "Open a built-in synthetic volume instead (head)")
        ->check(CLI::IsMember(io::builtin_phantom_kinds()))
        ->excludes(sub->get_option("input"));
    sub->add_option("--script", args->script,
                    "Run these steps (one per line: open, wait idle, set, select, drag-threshold, orbit, view, "
                    "window-level, window-preset, pick, hide, show, branch-opacity, reset-styles, undo, redo, screenshot, "
                    "screenshot-window, save-session, "
                    "export-labels, export-tf, quit)")
        ->check(CLI::ExistingFile);
    sub->add_option("--frame-log", args->frame_log, "Write one line per UI frame: time, frame ms, running jobs");
    sub->add_option("--width", args->width, "Window width")->check(CLI::Range(640, 8192));
    sub->add_option("--height", args->height, "Window height")->check(CLI::Range(480, 8192));
    sub->add_flag("--no-recovery", args->no_recovery, "Neither autosave a recovery session nor offer one");
    sub->add_flag("--no-cache", args->no_cache, "Do not use the on-disk contour-tree cache");
    context.add_command(sub, [&context, args] { return run_view(context, *args); });
}

} // namespace arbor::cli
