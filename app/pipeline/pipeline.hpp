// pipeline.hpp - the one object every front (the CLI, the workstation, a
// study script) stands on: the user's choices (a Document), the latest
// result of every stage with the revisions it was computed from, and the
// jobs computing the stale ones.
//
//   Pipeline p(registry, options);
//   p.set_document(doc);                       // checked, revisions bumped per changed group
//   auto image = p.run<Stage::Render>();       // runs import .. render, or what is stale of it
//   p.set_view(v);  p.run<Stage::Render>();    // renders again, nothing else
//
// request() starts a job per stale stage up to the one asked for and
// returns that stage's job at once; run() also waits for it.  A stage whose
// inputs did not change is served from its cached result; one already being
// computed for the same inputs is joined, not started twice; a request for a
// stage with different inputs cancels the older job of that stage still
// running (a newer slider position wins).  Jobs of one stage run one at a
// time (they share the stage's plugin instances); jobs of different stages
// run in parallel.  Results are immutable snapshots another thread may read
// while the next job runs.
//
// Thread-safety: every member function may be called from any thread.
#pragma once

#include "document.hpp"
#include "job.hpp"
#include "render_scene.hpp"
#include "plugin_catalog.hpp"
#include "stage_graph.hpp"
#include "stage_results.hpp"

#include <array>
#include <atomic>
#include <filesystem>
#include <functional>
#include <stop_token>
#include <list>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace arbor::pipeline {

// One pass of the document's view, as Pipeline::render_pass renders it: the
// request (scene->request) and everything it points into.
struct PassScene {
    std::shared_ptr<const TransferFunctionsResult> tf;
    std::shared_ptr<const LabelsResult> labels;
    std::shared_ptr<const FilterResult> filtered;
    std::shared_ptr<const TransferFunctions> functions;
    arbor_camera camera{};
    std::unique_ptr<RenderScene> scene;
    PluginSetting renderer;
    uint32_t width = 0, height = 0; // the view
};

struct PipelineOptions {
    uint64_t max_volume_bytes = uint64_t{1} << 34;
    // The on-disk cache of contour trees; empty: none (always recompute).
    std::filesystem::path tree_cache_folder;
    uint64_t tree_cache_max_bytes = uint64_t{4} << 30;
    // Where every job's progress and log also go (a terminal); may be null
    // (the log then goes to the host log).
    ProgressSink *progress = nullptr;
    LogSink *log = nullptr;
    // A one-shot front (`arbor run`) sets it: the front makes one pass -
    // one input through one filter chain, then one document or a sweep of
    // documents that differ below the contour tree (simplifier, cut, look,
    // view) - and ends.  A result that no later stage of the pass reads is
    // then let go as soon as its last reader is through, instead of being
    // kept for a change of the choices that will not come:
    //  - the imported voxels, once the filter chain has made a volume of its
    //    own (the import's result is dropped: the report and the session
    //    keep the import's description, not its voxels);
    //  - the contour tree's segmentation (vertex_arc, 4 bytes a voxel), once
    //    the cut of the pass's last document (declare_last_document) has
    //    made its label map: the tree's latest result becomes the tree
    //    without its segmentation (its nodes and arcs, timings, seconds) and
    //    is no longer current.
    // So the render does not hold the input or the segmentation beside the
    // filtered volume, the label map and the renderer's own copies.  A
    // later request of what was let go computes it again: a changed chain
    // imports again, a tree or a new decomposition or cut computes the tree
    // again (or reads it from the on-disk cache).  Fronts that keep results
    // for the next change (the workstation, `arbor compare`) leave it off:
    // nothing is then let go.
    bool single_pass = false;
    // Added to the nice value of every job's thread (core/thread_priority.hpp):
    // the workstation's UI stays responsive while jobs use every core.
    int worker_nice = 0;
    // Inputs named by a URI ("pacs://NODE/SERIES"): turns one into a local
    // file or folder, reporting to the job and polling the token.  The
    // front that knows the scheme sets it (the CLI and the workstation:
    // dicom/pacs_input.hpp); without it such an input is an error.
    std::function<std::filesystem::path(const std::string &uri, ProgressSink &progress, std::stop_token stop)>
        fetch_input;
};

class Pipeline {
public:
    Pipeline(const PluginRegistry &registry, PipelineOptions options = {});
    ~Pipeline(); // cancels every job and waits for them
    Pipeline(const Pipeline &) = delete;
    Pipeline &operator=(const Pipeline &) = delete;

    const PluginCatalog &catalog() const { return catalog_; }
    const PipelineOptions &options() const { return options_; }

    // The choices.  Setting resolves every plugin setting through the
    // catalog first (std::invalid_argument for an unknown plugin or a bad
    // value; the document is then left as it was) and bumps the revision of
    // each group whose value changed; setting equal values changes nothing.
    Document document() const;
    void set_document(const Document &document);
    void set_input(const InputChoice &input);
    void set_filters(const std::vector<PluginSetting> &filters);
    void set_simplifier(const PluginSetting &simplifier);
    void set_cut(const CutChoice &cut);
    void set_appearance(const Appearance &appearance);
    void set_view(const ViewChoice &view);
    std::array<uint64_t, kGroupCount> revisions() const;

    // Single pass (PipelineOptions::single_pass): the document now set is
    // the pass's last - the front sets no other before it ends (a sweep
    // says so at its last point, a run of one document at once).  Once the
    // cut of this document is made (at once when it already is), the
    // contour tree's segmentation goes: no later stage reads it.  Setting a
    // different document afterwards takes the declaration back.  Throws
    // std::logic_error on a pipeline that is not single-pass.
    void declare_last_document();

    // Starts what is stale up to `stage`; returns the stage's job (already
    // ended when its result was current).
    std::shared_ptr<Job> request(Stage stage);
    // request() and wait: the stage's result, or its (or an upstream
    // stage's) error; Cancelled when cancelled.
    template <Stage S> std::shared_ptr<const StageResult<S>> run()
    {
        return std::static_pointer_cast<const StageResult<S>>(request(S)->wait());
    }

    // The newest finished result of a stage, current or not (null if none).
    template <Stage S> std::shared_ptr<const StageResult<S>> latest() const
    {
        return std::static_pointer_cast<const StageResult<S>>(latest_result(S));
    }
    bool is_current(Stage stage) const;

    // Jobs waiting or running, oldest first.
    std::vector<std::shared_ptr<Job>> active_jobs() const;
    void cancel_all();

    // One pass of the document's view through the render stage's own
    // renderer (it waits while a render job holds it), for a front that
    // refines progressively: no second renderer keeps a second copy of the
    // volume.  The transfer functions are the document's (run if stale),
    // scaled by the latest render's balance when it balanced the same
    // branches; the camera is the latest render's when that render is
    // current, else the document's orbit zoomed by the latest framing.
    // `frame` is resized to the view (and must hold the previous pass for
    // SUPERSAMPLE).  Throws Cancelled when stopped.
    void render_pass(RenderedImage &frame, const FramePass &pass, std::stop_token stop = {});
    // What render_pass renders (the same functions, camera and view size),
    // for a front that renders it with a renderer instance of its own (into
    // its OpenGL context).  Throws Cancelled when stopped.
    std::unique_ptr<PassScene> pass_scene(std::stop_token stop = {});
    // A pass that needs no topology: the filtered volume (imported and
    // filtered first, if stale) with one transfer function from its values
    // (preview_functions.hpp), no labels, from the document's orbit; for
    // the seconds while the contour tree is computed.  Throws Cancelled.
    void preview_pass(RenderedImage &frame, const FramePass &pass, std::stop_token stop = {});

    // The camera render_pass renders from now (the latest render's when it
    // is current); throws std::logic_error before there is a volume.
    arbor_camera camera() const;

    // Per stage: how many times it was computed (not served from its cache).
    std::array<uint64_t, kStageCount> stage_runs() const;

private:
    struct Slot; // per stage: result, active jobs, plugin instances, the lock its jobs take
    struct Worker {
        // What the thread leaves as its last act.  It lets go of its job, so
        // that a finished job's result lives only as long as those who asked
        // for it hold it; a failed job is handed over here instead and let
        // go by the front that reaps the worker (the error may be in a
        // front's handler, and the exception's count is one TSan cannot
        // see).  Then `exited` is set: joining cannot wait on freeing a
        // large result.
        struct Exit {
            std::shared_ptr<Job> failed;
            std::atomic<bool> exited{false};
        };
        std::unique_ptr<Exit> exit; // outlives the thread: joined before it goes
        std::thread thread;
    };

    std::shared_ptr<Job> ensure_locked(Stage stage, const std::shared_ptr<const Document> &document);
    void execute(const std::shared_ptr<Job> &job, std::shared_ptr<const Document> document,
                 std::vector<std::shared_ptr<Job>> upstream, StageKey key);
    std::shared_ptr<const void> latest_result(Stage stage) const;
    arbor_camera camera_for(const Document &document, const FilterResult &filtered) const;
    void reap_locked();
    // PipelineOptions::single_pass: drops the import's result after a
    // filter job made new voxels from it; returns it, to be freed outside
    // the lock.
    std::shared_ptr<const void> release_imported_voxels_locked(const std::shared_ptr<const void> &imported,
                                                               const std::shared_ptr<const void> &filtered);
    // PipelineOptions::single_pass: whether the cut of the declared last
    // document is made (its result current) and the tree's result still
    // holds its segmentation; that tree result, else null.
    std::shared_ptr<const void> segmentation_to_release_locked() const;
    // Puts the tree without its segmentation in place of `tree`, the tree
    // stage's result (unless another has replaced it meanwhile); `tree`'s
    // memory goes when its last reader lets go.  Takes the lock itself: the
    // copy of the nodes and arcs is made outside it.
    void release_segmentation(std::shared_ptr<const void> tree);
    void update(const Document &resolved);
    template <class T> void set_part(T Document::*part, const T &value);
    Document resolve(const Document &document) const;

    PluginCatalog catalog_;
    const PipelineOptions options_;

    mutable std::mutex mutex_; // the document, revisions, slots' results and job lists, workers
    Document document_;
    std::shared_ptr<const Document> snapshot_;
    std::array<uint64_t, kGroupCount> revisions_{};
    uint64_t revision_counter_ = 0;
    uint64_t job_counter_ = 0;
    bool last_document_ = false; // declare_last_document, until the document changes
    std::array<std::unique_ptr<Slot>, kStageCount> slots_;
    std::list<Worker> workers_;
};

} // namespace arbor::pipeline
