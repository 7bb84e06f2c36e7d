#include "stage_compute.hpp"

#include "volume_checksum.hpp"

#include "branch_style.hpp"
#include "context_structures.hpp"
#include "flow_peel.hpp"
#include "memory_plan.hpp"

#include "render_scene.hpp"
#include "transfer_function_file.hpp"
#include "tree_cache.hpp"

#include "core/available_memory.hpp"
#include "core/body_region.hpp"
#include "core/cancelled.hpp"
#include "core/stopwatch.hpp"
#include "host/filter_run.hpp"
#include "host/simplifier_importance.hpp"
#include "host/volume_import.hpp"
#include "topology/label_thickness.hpp"
#include "io/phantom.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace arbor::pipeline {

namespace {

uint64_t next_revision()
{
    static std::atomic<uint64_t> counter{0};
    return ++counter;
}

topology::FieldView field_of(const Volume &v)
{
    return {v.type(), v.data(), static_cast<uint32_t>(v.voxel_count()), &v.geometry()};
}

std::shared_ptr<const void> import(StageContext &c)
{
    const InputChoice &in = c.document.input;
    Stopwatch watch;
    auto r = std::make_shared<ImportResult>();
    if (in.phantom) {
        io::PhantomOptions o;
        o.size = in.phantom->size;
        o.noise_sigma = in.phantom->noise;
        o.blobs = in.phantom->blobs;
        o.seed = in.phantom->seed;
        r->volume = std::make_shared<const Volume>(io::make_phantom(io::builtin_phantom(in.phantom->kind), o));
        r->source = "phantom:" + in.phantom->kind;
    } else {
        if (in.path.empty())
            throw std::invalid_argument("no input: give a volume file or folder, or --phantom head");
        std::filesystem::path local = in.path;
        if (is_input_uri(in.path.string())) {
            if (!c.options.fetch_input)
                throw std::invalid_argument(in.path.string() + ": this front cannot fetch inputs by URI");
            local = c.options.fetch_input(in.path.string(), c.job, c.stop());
        }
        PluginSetting setting = in.importer;
        const bool probed = setting.id.empty();
        setting.id = probed ? choose_importer(c.catalog.registry(), local)
                            : c.catalog.find(ARBOR_KIND_IMPORTER, setting.id);
        if (probed) { // the file chose the importer: say so when it lacks a parameter given
            const auto descriptions = c.catalog.descriptions(setting.id);
            for (const auto &[key, value] : setting.params)
                if (std::none_of(descriptions.begin(), descriptions.end(), [&](auto *d) { return key == d->id; }))
                    throw SettingError(SettingError::Problem::Unknown, setting.id, key,
                                       in.path.string() + " is read by " + setting.id + ", which has no parameter '" +
                                           key + "'");
        }
        PluginSlot::Lease importer = c.plugins.lease(setting, &c.job);
        require_parameters(*importer, setting);
        Volume volume = import_volume(*importer, local, &c.job, c.options.max_volume_bytes, c.stop(),
                                      [&c](const arbor_volume &header) { return admit_volume(header, c.document); });
        if (volume.mapping().unit.empty()) {
            r->hounsfield_inferred = infer_hounsfield(volume);
            if (r->hounsfield_inferred) {
                volume.mapping().unit = "HU";
                c.job.write(ARBOR_LOG_INFO, "",
                            "values read as Hounsfield units: the file names no unit, and they are a CT's (" +
                                r->hounsfield_inferred->describe() + ")");
            }
        }
        r->volume = std::make_shared<const Volume>(std::move(volume));
        r->source = in.path.string();
        r->importer = {setting.id, importer->descriptor().version, read_params(*importer)};
    }
    r->checksum = volume_checksum(*r->volume);
    r->seconds = watch.lap();
    return r;
}

std::shared_ptr<const void> filter(StageContext &c)
{
    const auto imported = c.input<Stage::Import>();
    Stopwatch watch;
    auto r = std::make_shared<FilterResult>();
    r->volume = imported->volume;
    r->source = imported->source;
    std::vector<PluginSetting> chain = c.document.filters;
    if (chain.empty() && c.document.auto_denoise) {
        // Denoise only what noise dominates, as strongly as the study's plateau.
        c.job.report("looking at the noise", 0.0);
        PluginSetting gaussian;
        try {
            gaussian = c.catalog.resolve(ARBOR_KIND_FILTER, {"org.arbor.filter.gaussian", "", {}});
        } catch (const std::invalid_argument &) {
            c.job.write(ARBOR_LOG_INFO, "", "no gaussian filter installed: not denoising automatically");
        }
        if (!gaussian.empty()) {
            const auto smooth = [&](const Volume &v, double sigma) {
                PluginSetting s = gaussian;
                char text[40];
                std::snprintf(text, sizeof text, "%.17g", sigma);
                s.params["sigma"] = text;
                PluginSlot::Lease f = c.plugins.lease(s, &c.job);
                return run_filter(*f, v, nullptr, c.options.max_volume_bytes, c.stop());
            };
            r->denoise = advise_denoising(*imported->volume, smooth, c.stop());
            c.job.write(ARBOR_LOG_INFO, "", "automatic denoising: " + r->denoise->describe());
            if (r->denoise->sigma_mm > 0) {
                char text[40];
                std::snprintf(text, sizeof text, "%.17g", r->denoise->sigma_mm);
                gaussian.params["sigma"] = text;
                chain.push_back(gaussian);
            }
        }
        c.job.finish();
    }
    for (const PluginSetting &setting : chain) {
        throw_if_stopped(c.stop());
        PluginSlot::Lease f = c.plugins.lease(setting, &c.job);
        r->volume = std::make_shared<const Volume>(
            run_filter(*f, *r->volume, &c.job, c.options.max_volume_bytes, c.stop()));
        r->source += " | " + describe_setting(setting, f->param_descriptions()) +
                     (c.document.filters.empty() ? " (automatic)" : "");
        r->filters.push_back(setting);
    }
    r->background = estimate_background(*r->volume);
    r->body = std::make_shared<const BodyRegion>(*r->volume, r->background ? r->background->level
                                                                            : std::numeric_limits<double>::quiet_NaN());
    r->revision = next_revision();
    r->seconds = watch.lap();
    return r;
}

// From the on-disk cache when it holds the tree of these very voxels;
// otherwise computed, then stored there.  A cache that cannot be read or
// written costs a warning, never the result.
std::shared_ptr<const void> contour_tree(StageContext &c)
{
    const Volume &volume = *c.input<Stage::Filter>()->volume;
    auto r = std::make_shared<ContourTreeResult>();
    Stopwatch watch;
    std::optional<TreeCache> cache;
    std::string key;
    if (!c.options.tree_cache_folder.empty() && volume.voxel_count() > 0) {
        cache.emplace(c.options.tree_cache_folder, c.options.tree_cache_max_bytes);
        key = tree_cache_key(volume);
        std::string why;
        c.job.report("reading the cached contour tree", 0.0);
        if (std::optional<topology::ContourTree> t = cache->load(key, volume.voxel_count(), &why, c.stop())) {
            c.job.finish();
            r->tree = std::move(*t);
            r->from_cache = true;
            r->seconds = watch.lap();
            r->timings.push_back({"cache read", r->seconds});
            return r;
        }
        c.job.finish();
        throw_if_stopped(c.stop());
        if (why.rfind("unusable", 0) == 0)
            c.job.write(ARBOR_LOG_WARNING, "contour-tree cache", why + "; computing the tree again");
    }
    require_tree_memory(volume);
    topology::TopologyResult t = topology::compute_contour_tree(
        volume, [&c](const char *stage, double f) { c.job.report(stage, f); }, c.stop(), available_memory_bytes());
    c.job.finish();
    r->tree = std::move(t.tree);
    r->timings = std::move(t.timings);
    r->memory_plan = topology::tree_memory_plan_name(t.plan);
    r->seconds = watch.lap();
    if (cache) {
        try {
            cache->store(key, r->tree);
        } catch (const std::exception &e) {
            c.job.write(ARBOR_LOG_WARNING, "contour-tree cache", std::string("not stored: ") + e.what());
        }
    }
    return r;
}

std::shared_ptr<const void> decomposition(StageContext &c)
{
    const auto tree = c.input<Stage::ContourTree>();
    const Volume &volume = *c.input<Stage::Filter>()->volume;
    Stopwatch watch;
    auto r = std::make_shared<DecompositionResult>();
    PluginSlot::Lease simplifier = c.plugins.lease(c.document.simplifier, &c.job);
    r->simplifier = c.document.simplifier;
    r->simplifier_name = simplifier->descriptor().name;
    const topology::ImportanceFn importance = simplifier_importance(*simplifier, volume.mapping());
    const std::string activity = "branches by " + short_name(r->simplifier.id);
    const std::stop_token stop = c.stop();
    r->branches = topology::decompose_branches(tree->tree, field_of(volume), importance, [&](double f) {
        throw_if_stopped(stop);
        c.job.report(activity, f);
    });
    c.job.finish();
    r->seconds = watch.lap();
    return r;
}

std::shared_ptr<const void> cut(StageContext &c)
{
    const auto d = c.input<Stage::Decomposition>();
    const auto tree = c.input<Stage::ContourTree>();
    const Volume &volume = *c.input<Stage::Filter>()->volume;
    Stopwatch watch;
    auto r = std::make_shared<CutResult>();
    r->decomposition = d;
    r->requested = c.document.cut;
    // Not structures, never kept (their voxels go to their parents): the
    // background's basins and bumps (wholly at or below its level), and
    // pairs of equal values (plateaus split by simulation of simplicity:
    // no contrast at all).
    std::vector<bool> eligible(d->branches.branches.size(), true);
    const auto &background = c.input<Stage::Filter>()->background;
    const auto value = [&](uint32_t node) { return volume.value(tree->tree.node_vertex[node]); };
    for (std::size_t b = 1; b < eligible.size(); ++b) {
        const topology::Branch &br = d->branches.branches[b];
        if (br.measures[topology::kPersistence] <= 0) {
            eligible[b] = false;
        } else if (background && !r->requested.keep_background &&
                   std::max(value(br.saddle_node), value(br.extremum_node)) <= background->level) {
            eligible[b] = false;
            ++r->background_branches;
        }
    }
    // The knee chooses among structures big enough to be seen: a region of
    // fewer voxels than a 3x3x3 block is a speck (a partial-volume bump, a
    // noise pit), a pixel or two of any picture.  An explicit count or
    // threshold takes what it asks for.
    constexpr double kSpeck = 27;
    if (!r->requested.keep && !r->requested.threshold)
        for (std::size_t b = 1; b < eligible.size(); ++b)
            if (eligible[b] && d->branches.branches[b].measures[topology::kVolume] < kSpeck) {
                eligible[b] = false;
                ++r->speck_branches;
            }
    if (r->requested.keep) {
        r->cut = topology::cut_by_count(d->branches, *r->requested.keep, eligible);
    } else if (r->requested.threshold) {
        r->cut = topology::cut_by_threshold(d->branches, *r->requested.threshold, eligible);
    } else {
        r->knee = topology::knee_branch_count(d->branches, 6, 48, 50, eligible);
        r->cut = topology::cut_by_count(d->branches, r->knee->keep, eligible);
    }
    // The label map comes with the cut: the thickness of each structure,
    // which generators read, is measured on it.
    r->labels = std::make_shared<const LabelMap>(topology::label_voxels(tree->tree, d->branches, r->cut));
    const Geometry &g = volume.geometry();
    r->shapes = topology::label_shapes(*r->labels, g.dims, g.spacing, static_cast<uint32_t>(r->cut.kept.size()));
    if (const auto &body = c.input<Stage::Filter>()->body) {
        const std::vector<double> outside = body->outside_shares(*r->labels, static_cast<uint32_t>(r->shapes.size()));
        for (std::size_t l = 0; l < r->shapes.size(); ++l)
            r->shapes[l].outside_body = outside[l];
    }
    r->tree = std::make_unique<const BranchTreeRecord>(tree->tree, d->branches, r->cut, volume, &r->shapes);
    r->seconds = watch.lap();
    return r;
}

std::vector<std::string> kept_label_names(const topology::BranchDecomposition &d,
                                          const topology::SimplificationCut &cut)
{
    std::vector<std::string> names;
    names.reserve(cut.kept.size());
    for (const uint32_t b : cut.kept) {
        const topology::BranchKind k = d.branches[b].kind;
        names.push_back(k == topology::BranchKind::Root ? std::string("root")
                                                         : (k == topology::BranchKind::Maximum ? "max-" : "min-") +
                                                               std::to_string(b));
    }
    return names;
}

std::shared_ptr<const void> labels(StageContext &c)
{
    const auto cut = c.input<Stage::Cut>();
    Stopwatch watch;
    auto r = std::make_shared<LabelsResult>(cut);
    r->names = kept_label_names(cut->decomposition->branches, cut->cut);
    r->revision = next_revision();
    r->seconds = watch.lap();
    return r;
}

void check_selection(const Appearance &a, const CutResult &cut)
{
    if (a.selected && (*a.selected < 0 || static_cast<std::size_t>(*a.selected) >= cut.kept()))
        throw std::invalid_argument("selected branch " + std::to_string(*a.selected) + ": the simplified tree has " +
                                    std::to_string(cut.kept()) + " branches (0.." + std::to_string(cut.kept() - 1) +
                                    ")");
}

std::shared_ptr<const void> depiction(StageContext &c)
{
    const auto cut = c.input<Stage::Cut>();
    const Appearance &a = c.document.appearance;
    check_selection(a, *cut);
    Stopwatch watch;
    auto r = std::make_shared<DepictionResult>();
    r->cut = cut;
    r->depictor = a.depictor;
    r->request.struct_size = sizeof r->request;
    r->request.selected_branch = a.selected.value_or(-1);
    r->request.tree = &cut->tree->record();
    auto record = std::make_unique<DepictionRecord>(cut->tree->size());
    if (!a.depictor.empty()) {
        PluginSlot::Lease depictor = c.plugins.lease(a.depictor, &c.job);
        depict(*depictor, r->request, *record, &c.job, c.stop());
    }
    r->depiction = std::move(record);
    r->seconds = watch.lap();
    return r;
}

// The generator's parameter the balance is taken at the default of.
constexpr const char *kFlowRate = "flow-rate";

std::shared_ptr<const void> transfer_functions(StageContext &c)
{
    const auto depicted = c.input<Stage::Depiction>();
    const Volume &volume = *c.input<Stage::Filter>()->volume;
    const Appearance &a = c.document.appearance;
    const CutResult &cut = *depicted->cut;
    Stopwatch watch;
    auto r = std::make_shared<TransferFunctionsResult>();
    r->depiction = depicted;
    r->value_range = {cut.decomposition->branches.global_min, cut.decomposition->branches.global_max};
    if (!a.transfer_functions_file.empty()) {
        // Functions made (and perhaps edited) earlier, for these very branches.
        StoredTransferFunctions stored = read_transfer_functions(a.transfer_functions_file);
        const arbor_branch_tree &tree = cut.tree->record();
        bool same = stored.extremum_vertex.size() == tree.branch_count;
        for (uint32_t k = 0; same && k < tree.branch_count; ++k)
            same = stored.extremum_vertex[k] == tree.extremum_vertex[k];
        if (!same)
            throw std::invalid_argument(
                a.transfer_functions_file.string() + ": its " + std::to_string(stored.extremum_vertex.size()) +
                " branches (made from " + stored.source + ") are not the branches " + cut.decomposition->simplifier.id +
                " keeps in " + c.input<Stage::Filter>()->source + " with " + cut.effective().describe() +
                "; regenerate them with `arbor tf`");
        if (!stored.rebaked.empty()) {
            std::string labels;
            for (const uint32_t b : stored.rebaked)
                labels += (labels.empty() ? "" : ", ") + std::to_string(b);
            c.job.write(ARBOR_LOG_INFO, "",
                        a.transfer_functions_file.string() + ": the control points of branch" +
                            (stored.rebaked.size() > 1 ? "es " : " ") + labels +
                            " were edited; their lookup tables were rebaked from the points");
        }
        r->file = a.transfer_functions_file;
        r->functions = std::move(stored.functions);
        r->seconds = watch.lap();
        return r;
    }
    PluginSlot::Lease generator = c.plugins.lease(a.generator, &c.job);
    r->generator = a.generator;
    const arbor_volume view = volume.view();
    arbor_tf_request request{};
    request.struct_size = sizeof request;
    request.tree = &cut.tree->record();
    request.depiction = a.depictor.empty() ? nullptr : &depicted->depiction->record();
    request.volume = &view;
    request.value_range[0] = r->value_range[0];
    request.value_range[1] = r->value_range[1];
    const auto &sp = volume.geometry().spacing;
    request.min_spacing = std::min({sp[0], sp[1], sp[2]});
    const auto &background = c.input<Stage::Filter>()->background;
    request.background_level = background ? background->level : std::numeric_limits<double>::quiet_NaN();
    request.background_peak = background ? background->peak : std::numeric_limits<double>::quiet_NaN();
    // The visibility balance is taken at the generator's default flow rate
    // (flow_peel.hpp): when the document moves it, those functions too.
    if (const arbor_param_desc *d = generator->find_param(kFlowRate);
        d && d->type == ARBOR_PARAM_FLOAT && d->components == 1 && d->default_value[0] > 0) {
        const arbor_param_value q = generator->get_param(kFlowRate);
        if (q.number[0] != d->default_value[0]) {
            arbor_param_value q0 = q;
            q0.number[0] = d->default_value[0];
            generator->set_param(kFlowRate, q0);
            auto reference = std::make_shared<TransferFunctions>(cut.tree->size(), a.lut_size, request.min_spacing);
            generate_transfer_functions(*generator, request, *reference, &c.job, c.stop());
            generator->set_param(kFlowRate, q);
            r->reference = std::move(reference);
            r->flow_ratio = q.number[0] / q0.number[0];
        }
    }
    auto functions = std::make_shared<TransferFunctions>(cut.tree->size(), a.lut_size, request.min_spacing);
    generate_transfer_functions(*generator, request, *functions, &c.job, c.stop());
    r->functions = std::move(functions);
    r->seconds = watch.lap();
    return r;
}

// What the render stage keeps between its jobs: the balance of the last
// transfer functions, labels and renderer, so an orbiting camera does not
// balance again.
struct BalanceMemo {
    std::shared_ptr<const TransferFunctionsResult> tf; // balanced at its default flow rate
    uint64_t labels_revision = 0;
    PluginSetting renderer;
    std::optional<int32_t> selected;
    bool asked = false;    // for balancing
    bool balanced = false; // and got it (a renderer that measures no visibility gives none)
    BalanceResult balance;
    std::optional<ViewpointChoice> viewpoint; // chosen once for these functions
};

// Whether two transfer-function results differ at most in the flow rate,
// so that the balance of one, taken at the default flow rate, holds for
// the other (flow_peel.hpp).  Functions read from a file: only the same.
bool same_but_flow_rate(const TransferFunctionsResult &a, const TransferFunctionsResult &b)
{
    if (&a == &b)
        return true;
    if (!a.file.empty() || !b.file.empty() || a.depiction != b.depiction || a.value_range != b.value_range ||
        a.functions->lut_size() != b.functions->lut_size())
        return false;
    PluginSetting x = a.generator, y = b.generator;
    x.params.erase(kFlowRate);
    y.params.erase(kFlowRate);
    return x == y;
}

// The user's zoom, on top of the framing: closer, or a smaller view.
arbor_camera zoomed(arbor_camera c, double zoom)
{
    if (!(zoom > 0) || zoom == 1.0)
        return c;
    if (c.projection == ARBOR_PROJECTION_PERSPECTIVE)
        for (int a = 0; a < 3; ++a)
            c.position[a] = c.focal_point[a] + (c.position[a] - c.focal_point[a]) / zoom;
    else
        c.parallel_scale /= zoom;
    return c;
}

std::shared_ptr<const void> render(StageContext &c)
{
    const auto tf = c.input<Stage::TransferFunctions>();
    const auto labels = c.input<Stage::Labels>();
    const auto filtered = c.input<Stage::Filter>();
    const Volume &volume = *filtered->volume;
    const ViewChoice &v = c.document.view;
    Stopwatch watch;
    auto r = std::make_shared<RenderResult>();
    r->renderer = v.renderer;
    PluginSlot::Lease renderer = c.plugins.lease(v.renderer, &c.job);
    RenderScene scene(*filtered, *labels, tf->functions->branch_count(), v.background);
    arbor_render_request &request = scene.request;
    // Previews see a clear background, so opacity is what was seen.
    arbor_render_request preview_request = request;
    std::fill(std::begin(preview_request.background), std::end(preview_request.background), 0.0f);
    const auto preview = [&](const TransferFunctions &functions, const arbor_camera &camera, uint32_t w,
                             uint32_t h) {
        arbor_render_request p = preview_request;
        p.transfer_functions = &functions.record();
        p.camera = &camera;
        return render_image(*renderer, p, w, h, nullptr, c.stop());
    };

    r->functions = tf->functions;
    auto *memo = std::any_cast<BalanceMemo>(&c.memo);
    const bool balance = c.document.appearance.balance_visibility;
    const std::optional<int32_t> &selected = c.document.appearance.selected;
    if (!memo || !same_but_flow_rate(*memo->tf, *tf) || memo->labels_revision != labels->revision ||
        memo->renderer != v.renderer || memo->selected != selected || memo->asked != balance) {
        c.memo = BalanceMemo{tf, labels->revision, v.renderer, selected, balance, balance, {}, std::nullopt};
        memo = std::any_cast<BalanceMemo>(&c.memo);
        if (balance) {
            c.job.report("balancing visibility", 0.0);
            try {
                const CutResult &cut = *tf->depiction->cut;
                const arbor_branch_tree &t = cut.tree->record();
                BranchLayout layout;
                layout.parent.assign(t.parent, t.parent + t.branch_count);
                layout.voxels.assign(t.branch_count, 0.0);
                for (const uint32_t l : *cut.labels)
                    layout.voxels[l] += 1;
                for (std::size_t b = 0; b < cut.shapes.size(); ++b) {
                    const topology::LabelShape &shape = cut.shapes[b];
                    layout.sheet.push_back(shape.compactness > 0 && shape.compactness < 0.2);
                    layout.context.push_back(
                        b < t.branch_count &&
                        context_reason(shape, t.extremum_kind[b] == ARBOR_EXTREMUM_MAXIMUM, b == 0) !=
                            ContextReason::None);
                }
                BalanceTargets targets;
                if (c.document.appearance.selected && *c.document.appearance.selected > 0)
                    targets.focus = *c.document.appearance.selected;
                memo->balance = balance_visibility(
                    tf->balanced_at(), layout, volume.geometry(),
                    [&](const TransferFunctions &f, const arbor_camera &cam, uint32_t size) {
                        return preview(f, cam, size, size);
                    },
                    targets, c.stop());
            } catch (const std::invalid_argument &e) {
                c.job.write(ARBOR_LOG_INFO, "", std::string("visibility not balanced: ") + e.what());
                memo->balanced = false;
            }
        }
    }
    if (memo->balanced) {
        r->balance = memo->balance;
        if (tf->flow_ratio != 1.0)
            r->peel = flow_peel(tf->depiction->cut->tree->record(), tf->flow_ratio);
        r->functions = tf->functions->with_optical_depth(peeled_scale(memo->balance.scale, r->peel));
    }
    // A person's edits of single structures, on top (framing sees them too).
    r->functions = styled(r->functions, tf->depiction->cut->tree->record(), v.branch_styles);
    request.transfer_functions = &r->functions->record();

    Orbit orbit = v.orbit;
    orbit.zoom = 1.0;
    if (v.auto_view) {
        if (!memo->viewpoint) {
            c.job.report("choosing the view", 0.0);
            std::vector<double> voxels(tf->functions->branch_count(), 0.0);
            for (const uint32_t l : labels->labels)
                voxels[l] += 1;
            memo->viewpoint = choose_viewpoint(
                volume.geometry(), voxels,
                [&](const arbor_camera &cam, uint32_t size) { return preview(*r->functions, cam, size, size); },
                c.stop());
        }
        r->viewpoint = memo->viewpoint;
        orbit.azimuth = memo->viewpoint->azimuth;
        orbit.elevation = memo->viewpoint->elevation;
    }
    arbor_camera camera = orbit_camera(volume.geometry(), orbit);
    if (v.frame_content) {
        c.job.report("framing", 0.0);
        // Twice: a perspective view is framed exactly only at the focal plane.
        const double longer = std::max(v.width, v.height);
        const uint32_t pw = std::max(16u, static_cast<uint32_t>(std::lround(128.0 * v.width / longer)));
        const uint32_t ph = std::max(16u, static_cast<uint32_t>(std::lround(128.0 * v.height / longer)));
        for (int pass = 0; pass < 2; ++pass) {
            const std::optional<Framing> f =
                frame_content(camera, preview(*r->functions, camera, pw, ph), v.width, v.height);
            if (!f)
                break;
            if (!r->framing)
                r->framing = f;
            r->framing->scale = pass == 0 ? f->scale : r->framing->scale * f->scale;
            r->framing->camera = camera = f->camera;
        }
    }
    r->camera = zoomed(camera, v.orbit.zoom);
    request.camera = &r->camera;
    r->image = render_image(*renderer, request, v.width, v.height, &c.job, c.stop());
    r->seconds = watch.lap();
    return r;
}

std::shared_ptr<const void> legend(StageContext &c)
{
    const auto cut = c.input<Stage::Cut>();
    const Appearance &a = c.document.appearance;
    check_selection(a, *cut);
    if (a.legend.empty())
        throw std::invalid_argument("no legend depictor chosen");
    Stopwatch watch;
    auto r = std::make_shared<LegendResult>();
    r->depictor = a.legend;
    // Around the selected branch, or the deepest one (the innermost structure).
    const arbor_branch_tree &tree = cut->tree->record();
    for (uint32_t b = 0; b < tree.branch_count; ++b)
        if (tree.depth[b] > tree.depth[r->selected])
            r->selected = b;
    if (a.selected)
        r->selected = static_cast<uint32_t>(*a.selected);
    r->size = a.legend_size;
    r->rgba.assign(std::size_t{r->size} * r->size * 4, 0.0f);
    arbor_depiction_request request{};
    request.struct_size = sizeof request;
    request.selected_branch = static_cast<int32_t>(r->selected);
    request.tree = &tree;
    arbor_image image{};
    image.struct_size = sizeof image;
    image.width = image.height = r->size;
    image.row_stride = 4 * static_cast<int64_t>(r->size);
    image.rgba = r->rgba.data();
    PluginSlot::Lease depictor = c.plugins.lease(a.legend, &c.job);
    const auto &table = depictor->interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
    Task task(&c.job, c.stop());
    const arbor_status s = depictor->call("depictor.legend", table.legend, &request, &image, task.get());
    if (s == ARBOR_ERROR_UNSUPPORTED)
        throw std::invalid_argument(depictor->id() + " draws no legend");
    depictor->check(s, "drawing the legend");
    r->seconds = watch.lap();
    return r;
}

} // namespace

std::shared_ptr<const void> compute_stage(Stage stage, StageContext &context)
{
    switch (stage) {
    case Stage::Import: return import(context);
    case Stage::Filter: return filter(context);
    case Stage::ContourTree: return contour_tree(context);
    case Stage::Decomposition: return decomposition(context);
    case Stage::Cut: return cut(context);
    case Stage::Labels: return labels(context);
    case Stage::Depiction: return depiction(context);
    case Stage::TransferFunctions: return transfer_functions(context);
    case Stage::Render: return render(context);
    case Stage::Legend: return legend(context);
    }
    throw std::logic_error("unknown stage");
}

} // namespace arbor::pipeline
