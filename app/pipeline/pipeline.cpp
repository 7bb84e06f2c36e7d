#include "pipeline.hpp"

#include "branch_style.hpp"
#include "flow_peel.hpp"
#include "preview_functions.hpp"
#include "render_scene.hpp"
#include "stage_compute.hpp"

#include "core/cancelled.hpp"
#include "core/thread_priority.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace arbor::pipeline {

struct Pipeline::Slot {
    explicit Slot(const PluginCatalog &catalog) : plugins(catalog) {}

    // Under the pipeline's mutex:
    std::shared_ptr<const void> result; // the newest finished result
    StageKey key{};                     // the revisions it was computed from
    uint64_t result_serial = 0;         // the job that computed it
    bool has_result = false;
    std::vector<std::pair<StageKey, std::shared_ptr<Job>>> active; // waiting or running
    uint64_t runs = 0;

    // Held by the job computing; with it, the stage's plugin instances and
    // whatever else it keeps between its jobs.
    std::mutex busy;
    PluginSlot plugins;
    std::any memo;
};

Pipeline::Pipeline(const PluginRegistry &registry, PipelineOptions options)
    : catalog_(registry), options_(std::move(options)), snapshot_(std::make_shared<const Document>())
{
    for (auto &slot : slots_)
        slot = std::make_unique<Slot>(catalog_);
}

Pipeline::~Pipeline()
{
    std::list<Worker> workers;
    {
        std::lock_guard lock(mutex_);
        for (auto &slot : slots_)
            for (auto &[key, job] : slot->active)
                job->cancel();
        workers.swap(workers_);
    }
    for (Worker &w : workers)
        w.thread.join();
}

Document Pipeline::document() const
{
    std::lock_guard lock(mutex_);
    return document_;
}

std::array<uint64_t, kGroupCount> Pipeline::revisions() const
{
    std::lock_guard lock(mutex_);
    return revisions_;
}

Document Pipeline::resolve(const Document &d) const
{
    Document r = d;
    // The importer may stay unnamed (chosen by probing the file at import).
    if (!r.input.importer.empty())
        r.input.importer = catalog_.resolve(ARBOR_KIND_IMPORTER, r.input.importer);
    for (PluginSetting &f : r.filters)
        f = catalog_.resolve(ARBOR_KIND_FILTER, f);
    const auto required = [&](std::string_view kind, const PluginSetting &s) {
        if (s.empty())
            throw std::invalid_argument("no " + kind_noun(kind) + " chosen");
        return catalog_.resolve(kind, s);
    };
    r.simplifier = required(ARBOR_KIND_SIMPLIFIER, r.simplifier);
    r.appearance.generator = required(ARBOR_KIND_TF_GENERATOR, r.appearance.generator);
    r.view.renderer = required(ARBOR_KIND_RENDERER, r.view.renderer);
    if (!r.appearance.depictor.empty())
        r.appearance.depictor = catalog_.resolve(ARBOR_KIND_DEPICTOR, r.appearance.depictor);
    if (!r.appearance.legend.empty())
        r.appearance.legend = catalog_.resolve(ARBOR_KIND_DEPICTOR, r.appearance.legend);
    if (r.cut.keep && *r.cut.keep < 1)
        throw std::invalid_argument("a cut keeps at least 1 branch (the root)");
    if (r.cut.threshold && !(*r.cut.threshold >= 0.0 && *r.cut.threshold <= 1.0))
        throw std::invalid_argument("a cut threshold lies in [0, 1]");
    if (r.appearance.lut_size < 2 || r.appearance.lut_size > 65536)
        throw std::invalid_argument("lookup tables have 2 to 65536 entries");
    if (r.view.width < 1 || r.view.height < 1 || r.view.width > 16384 || r.view.height > 16384)
        throw std::invalid_argument("images are 1 to 16384 pixels wide and high");
    return r;
}

void Pipeline::update(const Document &resolved)
{
    std::lock_guard lock(mutex_);
    const auto bump = [&](Group g, bool changed) {
        if (changed) {
            revisions_[index_of(g)] = ++revision_counter_;
            last_document_ = false; // declared of the document before
        }
    };
    bump(Group::Input, resolved.input != document_.input);
    bump(Group::Filters, resolved.filters != document_.filters || resolved.auto_denoise != document_.auto_denoise);
    bump(Group::Simplifier, resolved.simplifier != document_.simplifier);
    bump(Group::Cut, resolved.cut != document_.cut);
    bump(Group::Appearance, resolved.appearance != document_.appearance);
    bump(Group::View, resolved.view != document_.view);
    document_ = resolved;
    snapshot_ = std::make_shared<const Document>(document_);
}

void Pipeline::set_document(const Document &document)
{
    update(resolve(document));
}

template <class T> void Pipeline::set_part(T Document::*part, const T &value)
{
    Document d = document();
    d.*part = value;
    set_document(d);
}

void Pipeline::set_input(const InputChoice &input)
{
    set_part(&Document::input, input);
}

void Pipeline::set_filters(const std::vector<PluginSetting> &filters)
{
    set_part(&Document::filters, filters);
}

void Pipeline::set_simplifier(const PluginSetting &simplifier)
{
    set_part(&Document::simplifier, simplifier);
}

void Pipeline::set_cut(const CutChoice &cut)
{
    set_part(&Document::cut, cut);
}

void Pipeline::set_appearance(const Appearance &appearance)
{
    set_part(&Document::appearance, appearance);
}

void Pipeline::set_view(const ViewChoice &view)
{
    set_part(&Document::view, view);
}

void Pipeline::declare_last_document()
{
    if (!options_.single_pass)
        throw std::logic_error("declare_last_document: the pipeline does not make a single pass");
    std::shared_ptr<const void> tree;
    {
        std::lock_guard lock(mutex_);
        last_document_ = true;
        tree = segmentation_to_release_locked();
    }
    // Its cut was made already (a sweep whose last points differ in the
    // look only): nothing will read the segmentation again.
    if (tree)
        release_segmentation(std::move(tree));
}

std::shared_ptr<Job> Pipeline::request(Stage stage)
{
    std::lock_guard lock(mutex_);
    reap_locked();
    return ensure_locked(stage, snapshot_);
}

std::shared_ptr<Job> Pipeline::ensure_locked(Stage stage, const std::shared_ptr<const Document> &document)
{
    Slot &slot = *slots_[index_of(stage)];
    const StageKey key = key_of(stage, revisions_);
    if (slot.has_result && slot.key == key)
        return Job::finished(stage, slot.result);
    for (auto &[k, job] : slot.active)
        if (k == key && !job->stop_token().stop_requested())
            return job; // already being computed for these inputs
    // A newer request for the stage: the older jobs' results would be stale.
    for (auto &[k, job] : slot.active)
        if (k != key)
            job->cancel();
    std::vector<std::shared_ptr<Job>> upstream;
    for (const Stage u : upstream_of(stage))
        upstream.push_back(ensure_locked(u, document));
    auto job = std::make_shared<Job>(stage, ++job_counter_, options_.progress, options_.log);
    slot.active.emplace_back(key, job);
    auto exit = std::make_unique<Worker::Exit>();
    Worker::Exit *leaving = exit.get();
    std::thread thread([this, job, document, upstream = std::move(upstream), key, leaving]() mutable {
        execute(job, std::move(document), std::move(upstream), key);
        if (job->state() == JobState::Failed)
            leaving->failed = std::move(job);
        job.reset();
        leaving->exited.store(true, std::memory_order_release);
    });
    workers_.push_back({std::move(exit), std::move(thread)});
    return job;
}

void Pipeline::execute(const std::shared_ptr<Job> &job, std::shared_ptr<const Document> document,
                       std::vector<std::shared_ptr<Job>> upstream, StageKey key)
{
    lower_thread_priority(options_.worker_nice);
    Slot &slot = *slots_[index_of(job->stage())];
    const auto leave = [&] {
        std::lock_guard lock(mutex_);
        std::erase_if(slot.active, [&](const auto &entry) { return entry.second == job; });
    };
    try {
        StageContext context{*document, catalog_, options_, *job, slot.plugins, slot.memo, {}};
        for (const std::shared_ptr<Job> &u : upstream)
            context.inputs[index_of(u->stage())] = u->wait(job->stop_token());
        upstream.clear(); // the results are held; the jobs may go
        std::unique_lock busy(slot.busy);
        throw_if_stopped(job->stop_token());
        job->start();
        std::shared_ptr<const void> result = compute_stage(job->stage(), context);
        // Freed below, not under the lock (they may be gigabytes).
        std::shared_ptr<const void> replaced, released, tree;
        {
            std::lock_guard lock(mutex_);
            ++slot.runs;
            if (job->serial() > slot.result_serial) {
                replaced = std::move(slot.result);
                slot.result = result;
                slot.key = key;
                slot.result_serial = job->serial();
                slot.has_result = true;
            }
            std::erase_if(slot.active, [&](const auto &entry) { return entry.second == job; });
            if (job->stage() == Stage::Filter && options_.single_pass)
                released = release_imported_voxels_locked(context.inputs[index_of(Stage::Import)], result);
            if (job->stage() == Stage::Cut && options_.single_pass)
                tree = segmentation_to_release_locked();
        }
        if (tree)
            release_segmentation(std::move(tree));
        // Released voxels and segmentation are gone before the stages
        // downstream start.
        context.inputs = {};
        released.reset();
        job->succeed(std::move(result));
    } catch (const Cancelled &) {
        leave();
        job->cancelled();
    } catch (...) {
        leave();
        job->fail(std::current_exception());
    }
}

std::shared_ptr<const void> Pipeline::release_imported_voxels_locked(const std::shared_ptr<const void> &imported,
                                                                    const std::shared_ptr<const void> &filtered)
{
    Slot &import = *slots_[index_of(Stage::Import)];
    const auto &in = *std::static_pointer_cast<const ImportResult>(imported);
    const auto &out = *std::static_pointer_cast<const FilterResult>(filtered);
    // Only the import this filter read, and only when the chain made new
    // voxels (an empty chain passes the import's own on).
    if (import.result != imported || out.volume == in.volume)
        return nullptr;
    import.has_result = false;
    return std::move(import.result);
}

std::shared_ptr<const void> Pipeline::segmentation_to_release_locked() const
{
    if (!options_.single_pass || !last_document_)
        return nullptr;
    const Slot &cut = *slots_[index_of(Stage::Cut)];
    const Slot &tree = *slots_[index_of(Stage::ContourTree)];
    // The last document's cut, made from the tree the stage holds now.
    if (!cut.has_result || cut.key != key_of(Stage::Cut, revisions_) || !tree.has_result ||
        tree.key != key_of(Stage::ContourTree, revisions_))
        return nullptr;
    if (std::static_pointer_cast<const ContourTreeResult>(tree.result)->tree.vertex_arc.empty())
        return nullptr;
    return tree.result;
}

namespace {

// The tree as the rest of a pass reads it (the report: its nodes and arcs,
// how long it took): everything but the per-voxel segmentation.
std::shared_ptr<const ContourTreeResult> without_segmentation(const ContourTreeResult &whole)
{
    auto r = std::make_shared<ContourTreeResult>();
    const topology::ContourTree &t = whole.tree;
    r->tree.node_vertex = t.node_vertex;
    r->tree.node_up = t.node_up;
    r->tree.node_down = t.node_down;
    r->tree.node_kind = t.node_kind;
    r->tree.arc_lo = t.arc_lo;
    r->tree.arc_hi = t.arc_hi;
    r->tree.node_arc_offsets = t.node_arc_offsets;
    r->tree.node_arcs = t.node_arcs;
    // vertex_arc: let go.
    r->timings = whole.timings;
    r->seconds = whole.seconds;
    r->from_cache = whole.from_cache;
    r->memory_plan = whole.memory_plan;
    return r;
}

} // namespace

void Pipeline::release_segmentation(std::shared_ptr<const void> tree)
{
    std::shared_ptr<const void> kept = without_segmentation(*std::static_pointer_cast<const ContourTreeResult>(tree));
    {
        std::lock_guard lock(mutex_);
        Slot &slot = *slots_[index_of(Stage::ContourTree)];
        if (slot.result != tree)
            return; // replaced meanwhile by a tree computed again: that one stays
        // Not current: a request that needs the tree computes it again.
        slot.result = std::move(kept);
        slot.has_result = false;
    }
    // `tree` is freed here, or by the last stage still reading it.
}

void Pipeline::reap_locked()
{
    // Only threads that are through: joining is then immediate (a front's
    // thread calls this, under the lock every accessor takes).
    for (auto it = workers_.begin(); it != workers_.end();) {
        if (it->exit->exited.load(std::memory_order_acquire)) {
            it->thread.join();
            it = workers_.erase(it);
        } else {
            ++it;
        }
    }
}

void Pipeline::preview_pass(RenderedImage &frame, const FramePass &pass, std::stop_token stop)
{
    const auto filtered = run<Stage::Filter>();
    const Document d = document();
    throw_if_stopped(stop);
    const std::unique_ptr<TransferFunctions> functions = preview_functions(*filtered);
    const arbor_camera camera = orbit_camera(filtered->volume->geometry(), d.view.orbit);
    const arbor_volume view = filtered->volume->view();
    arbor_render_request request{};
    request.struct_size = sizeof request;
    request.volume = &view;
    request.labels = nullptr; // every voxel the one function
    request.transfer_functions = &functions->record();
    request.camera = &camera;
    for (std::size_t i = 0; i < 4; ++i)
        request.background[i] = static_cast<float>(d.view.background[i]);
    request.volume_revision = filtered->revision;
    Slot &slot = *slots_[index_of(Stage::Render)];
    std::lock_guard busy(slot.busy);
    PluginSlot::Lease renderer = slot.plugins.lease(d.view.renderer, nullptr);
    frame.width = d.view.width;
    frame.height = d.view.height;
    frame.rgba.assign(std::size_t{frame.width} * frame.height * 4, 0.0f);
    frame.depth.assign(std::size_t{frame.width} * frame.height, std::numeric_limits<float>::infinity());
    render_region(*renderer, request, frame, {}, pass, nullptr, std::move(stop));
}

arbor_camera Pipeline::camera() const
{
    const auto filtered = latest<Stage::Filter>();
    if (!filtered)
        throw std::logic_error("no volume yet");
    return camera_for(document(), *filtered);
}

arbor_camera Pipeline::camera_for(const Document &d, const FilterResult &filtered) const
{
    const auto last = latest<Stage::Render>();
    if (last && is_current(Stage::Render))
        return last->camera;
    Orbit orbit = d.view.orbit;
    if (d.view.auto_view && last && last->viewpoint) {
        orbit.azimuth = last->viewpoint->azimuth;
        orbit.elevation = last->viewpoint->elevation;
    }
    orbit.zoom = (last && last->framing ? last->framing->scale : 1.0) * (orbit.zoom > 0 ? orbit.zoom : 1.0);
    return orbit_camera(filtered.volume->geometry(), orbit);
}

std::unique_ptr<PassScene> Pipeline::pass_scene(std::stop_token stop)
{
    auto p = std::make_unique<PassScene>();
    p->tf = run<Stage::TransferFunctions>();
    p->labels = run<Stage::Labels>();
    p->filtered = run<Stage::Filter>();
    const bool current = is_current(Stage::Render);
    const auto last = latest<Stage::Render>();
    const Document d = document();
    throw_if_stopped(stop);
    p->functions = p->tf->functions;
    if (current)
        p->functions = last->functions;
    else if (last && last->balance && last->balance->scale.size() == p->functions->branch_count())
        p->functions = p->functions->with_optical_depth(peeled_scale(
            last->balance->scale, flow_peel(p->tf->depiction->cut->tree->record(), p->tf->flow_ratio)));
    if (!current)
        p->functions = styled(p->functions, p->tf->depiction->cut->tree->record(), d.view.branch_styles);
    p->camera = camera_for(d, *p->filtered);
    p->scene = std::make_unique<RenderScene>(*p->filtered, *p->labels, p->functions->branch_count(), d.view.background);
    p->scene->request.transfer_functions = &p->functions->record();
    p->scene->request.camera = &p->camera;
    p->renderer = d.view.renderer;
    p->width = d.view.width;
    p->height = d.view.height;
    return p;
}

void Pipeline::render_pass(RenderedImage &frame, const FramePass &pass, std::stop_token stop)
{
    const std::unique_ptr<PassScene> p = pass_scene(stop);
    Slot &slot = *slots_[index_of(Stage::Render)];
    std::lock_guard busy(slot.busy);
    PluginSlot::Lease renderer = slot.plugins.lease(p->renderer, nullptr);
    if (frame.width != p->width || frame.height != p->height || pass.pass != ARBOR_RENDER_PASS_SUPERSAMPLE) {
        frame.width = p->width;
        frame.height = p->height;
        frame.rgba.assign(std::size_t{frame.width} * frame.height * 4, 0.0f);
        frame.depth.assign(std::size_t{frame.width} * frame.height, std::numeric_limits<float>::infinity());
    }
    render_region(*renderer, p->scene->request, frame, {}, pass, nullptr, std::move(stop));
}

std::shared_ptr<const void> Pipeline::latest_result(Stage stage) const
{
    std::lock_guard lock(mutex_);
    return slots_[index_of(stage)]->result;
}

bool Pipeline::is_current(Stage stage) const
{
    std::lock_guard lock(mutex_);
    const Slot &slot = *slots_[index_of(stage)];
    return slot.has_result && slot.key == key_of(stage, revisions_);
}

std::vector<std::shared_ptr<Job>> Pipeline::active_jobs() const
{
    std::vector<std::shared_ptr<Job>> out;
    {
        std::lock_guard lock(mutex_);
        for (const auto &slot : slots_)
            for (const auto &[key, job] : slot->active)
                out.push_back(job);
    }
    std::sort(out.begin(), out.end(), [](const auto &a, const auto &b) { return a->serial() < b->serial(); });
    return out;
}

void Pipeline::cancel_all()
{
    std::lock_guard lock(mutex_);
    for (const auto &slot : slots_)
        for (const auto &[key, job] : slot->active)
            job->cancel();
}

std::array<uint64_t, kStageCount> Pipeline::stage_runs() const
{
    std::lock_guard lock(mutex_);
    std::array<uint64_t, kStageCount> runs{};
    for (std::size_t s = 0; s < kStageCount; ++s)
        runs[s] = slots_[s]->runs;
    return runs;
}

} // namespace arbor::pipeline
