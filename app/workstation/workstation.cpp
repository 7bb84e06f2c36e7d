#include "workstation.hpp"

#include "branch_colors.hpp"
#include "controls.hpp"

#include "io/image_output.hpp"
#include "io/label_map_output.hpp"
#include "pipeline/session.hpp"
#include "pipeline/transfer_function_file.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace arbor::workstation {

namespace fs = std::filesystem;
using pipeline::Document;
using pipeline::Stage;

namespace {

// A file is a session when it is JSON naming the session format.
bool is_session_file(const fs::path &path)
{
    if (fs::is_directory(path))
        return false;
    std::ifstream in(path, std::ios::binary);
    char head[4096] = {};
    in.read(head, sizeof head - 1);
    const std::string text(head, static_cast<std::size_t>(in.gcount()));
    const auto first = text.find_first_not_of(" \t\r\n");
    return first != std::string::npos && text[first] == '{' && text.find(pipeline::kSessionFormat) != std::string::npos;
}

} // namespace

namespace {

// Jobs and renders run below the UI thread's priority, so frames keep coming.
constexpr int kBackgroundNice = 10;

pipeline::PipelineOptions background(pipeline::PipelineOptions o)
{
    o.worker_nice = kBackgroundNice;
    return o;
}

pipeline::ProgressiveView::Options progressive(std::shared_ptr<pipeline::FrameSurface> surface)
{
    pipeline::ProgressiveView::Options o;
    o.worker_nice = kBackgroundNice;
    o.preview = true; // a first image before the contour tree is done
    o.surface = std::move(surface);
    return o;
}

} // namespace

Workstation::Workstation(const PluginRegistry &registry, pipeline::PipelineOptions options)
    : pipeline_(registry, background(std::move(options))), history_(pipeline::default_document())
{
    // The pipeline resolves plugin names to full ids; the history holds
    // resolved documents, so that undo compares like with like.
    Document d = history_.current();
    pipeline_.set_document(for_pipeline(d));
    d = pipeline_.document();
    d.view.width = viewport_[0];
    d.view.height = viewport_[1];
    history_ = History(d);
    view3d_ = std::make_unique<pipeline::ProgressiveView>(pipeline_, progressive(nullptr));
}

void Workstation::draw_on(std::shared_ptr<pipeline::FrameSurface> surface,
                          std::function<RenderedImage(const GlFrame &)> read_back)
{
    const bool drawing = surface != nullptr;
    read_back_ = std::move(read_back);
    view3d_.reset(); // its thread lets the old surface go
    view3d_ = std::make_unique<pipeline::ProgressiveView>(pipeline_, progressive(std::move(surface)));
    if (drawing && has_input())
        touch_ = view3d_->touch();
}

Workstation::~Workstation()
{
    view3d_.reset(); // stops rendering before the pipeline goes
    pipeline_.cancel_all();
}

Document Workstation::for_pipeline(Document d) const
{
    d.view.width = viewport_[0];
    d.view.height = viewport_[1];
    return d;
}

void Workstation::show(const Document &document)
{
    pipeline_.set_document(for_pipeline(document));
    cancelled_ = false;
    if (!document.input.empty())
        touch_ = view3d_->touch();
}

void Workstation::say(arbor_log_level level, const std::string &text)
{
    messages_.push_back({level, text});
    while (messages_.size() > 200)
        messages_.pop_front();
}

std::string Workstation::input_name() const
{
    const auto &in = history_.current().input;
    if (in.phantom)
        return "phantom:" + in.phantom->kind;
    return in.path.string();
}

void Workstation::change(const Document &document, const std::string &what, bool commit)
{
    show(document); // throws before anything changes when the pipeline refuses it
    Document resolved = pipeline_.document();
    resolved.view.width = document.view.width;
    resolved.view.height = document.view.height;
    history_.set(resolved);
    if (commit)
        history_.commit(what);
    error_.clear();
}

void Workstation::commit(const std::string &what) { history_.commit(what); }

void Workstation::set(const std::string &name, const std::string &value, bool commit)
{
    Document d = history_.current();
    set_control(d, name, value, catalog());
    change(d, name + " " + value, commit);
}

bool Workstation::undo()
{
    const std::string what = history_.undo();
    if (what.empty())
        return false;
    show(history_.current());
    say(ARBOR_LOG_INFO, "undid " + what);
    return true;
}

bool Workstation::redo()
{
    const std::string what = history_.redo();
    if (what.empty())
        return false;
    show(history_.current());
    say(ARBOR_LOG_INFO, "redid " + what);
    return true;
}

void Workstation::open(const fs::path &path)
{
    if (!pipeline::is_input_uri(path.string()) && !fs::exists(path)) // pacs:// is fetched by the import job
        throw std::invalid_argument(path.string() + ": no such file or folder");
    if (is_session_file(path)) {
        pipeline::SessionRead read = pipeline::read_session(path, catalog());
        for (const std::string &w : read.warnings)
            say(ARBOR_LOG_WARNING, w);
        open_document(read.document, "open session " + path.filename().string());
        return;
    }
    // A new scan keeps the plugin choices but not what belonged to the old one.
    Document d = history_.current();
    d.input = {};
    d.input.path = path;
    d.appearance.selected.reset();
    d.cut = {};
    d.view.orbit = {};
    open_document(d, "open " + path.filename().string());
}

void Workstation::open_document(const Document &document, const std::string &what)
{
    change(document, what);
    filter_revision_ = 0; // the view state is set again for the new volume
    say(ARBOR_LOG_INFO, what);
}

void Workstation::select(std::optional<int32_t> label)
{
    Document d = history_.current();
    if (label && *label < 0)
        label.reset();
    if (d.appearance.selected == label)
        return;
    d.appearance.selected = label;
    change(d, label ? "select " + std::to_string(*label) : std::string("select none"));
}

namespace {

int64_t extremum_of(const pipeline::Pipeline &p, uint32_t label)
{
    const auto cut = p.latest<Stage::Cut>();
    if (!cut || label >= cut->kept())
        throw std::invalid_argument("branch " + std::to_string(label) + ": the simplified tree has " +
                                    std::to_string(cut ? cut->kept() : 0) + " branches");
    return cut->tree->record().extremum_vertex[label];
}

} // namespace

pipeline::BranchStyle Workstation::branch_style(uint32_t label) const
{
    const auto &styles = history_.current().view.branch_styles;
    const auto s = styles.find(extremum_of(pipeline_, label));
    return s == styles.end() ? pipeline::BranchStyle{} : s->second;
}

void Workstation::set_branch_style(uint32_t label, const pipeline::BranchStyle &style, bool commit)
{
    if (!(style.opacity >= 0 && style.opacity <= 100))
        throw std::invalid_argument("branch opacity must lie in [0, 100]");
    Document d = history_.current();
    const int64_t vertex = extremum_of(pipeline_, label);
    if (style == pipeline::BranchStyle{})
        d.view.branch_styles.erase(vertex);
    else
        d.view.branch_styles[vertex] = style;
    change(d, "style of branch " + std::to_string(label), commit);
}

void Workstation::reset_branch_styles()
{
    Document d = history_.current();
    d.view.branch_styles.clear();
    change(d, "reset the branch styles");
}

std::vector<bool> Workstation::hidden_labels() const
{
    std::vector<bool> out;
    const auto cut = pipeline_.latest<Stage::Cut>();
    const auto &styles = history_.current().view.branch_styles;
    if (!cut || styles.empty())
        return out;
    const arbor_branch_tree &t = cut->tree->record();
    out.resize(t.branch_count, false);
    for (uint32_t b = 0; b < t.branch_count; ++b)
        if (const auto s = styles.find(t.extremum_vertex[b]); s != styles.end())
            out[b] = !s->second.visible;
    return out;
}

void Workstation::drag_threshold(double fraction, bool commit)
{
    fraction = std::clamp(fraction, 0.0, 1.0);
    const auto decomposition = pipeline_.latest<Stage::Decomposition>();
    double top = 0;
    if (decomposition)
        for (std::size_t b = 1; b < decomposition->branches.branches.size(); ++b)
            if (std::isfinite(decomposition->branches.branches[b].importance))
                top = std::max(top, decomposition->branches.branches[b].importance);
    Document d = history_.current();
    d.cut.keep.reset();
    d.cut.threshold = std::clamp(fraction * (top > 0 ? top : 1.0), 0.0, 1.0);
    char what[64];
    std::snprintf(what, sizeof what, "threshold %.4g", *d.cut.threshold);
    change(d, what, commit);
}

void Workstation::orbit(double azimuth, double elevation, bool commit)
{
    Document d = history_.current();
    d.view.orbit.azimuth = std::remainder(azimuth, 360.0);
    d.view.orbit.elevation = std::clamp(elevation, -90.0, 90.0);
    d.view.auto_view = false;
    char what[64];
    std::snprintf(what, sizeof what, "orbit %.0f %.0f", d.view.orbit.azimuth, d.view.orbit.elevation);
    change(d, what, commit);
}

void Workstation::rotate(double d_azimuth, double d_elevation, bool commit)
{
    const auto &o = history_.current().view.orbit;
    orbit(o.azimuth + d_azimuth, o.elevation + d_elevation, commit);
}

void Workstation::zoom_by(double factor, bool commit)
{
    Document d = history_.current();
    d.view.orbit.zoom = std::clamp(d.view.orbit.zoom * factor, 0.05, 1000.0);
    change(d, "zoom", commit);
}

void Workstation::pan_by(double dx_mm, double dy_mm, bool commit)
{
    Document d = history_.current();
    d.view.orbit.pan_right += dx_mm;
    d.view.orbit.pan_up += dy_mm;
    change(d, "pan", commit);
}

void Workstation::standard_view(const std::string &name)
{
    static const std::vector<std::tuple<std::string, double, double>> views = {
        {"anterior", 0, 0},  {"posterior", 180, 0}, {"left", 90, 0},
        {"right", -90, 0},   {"superior", 0, 90},   {"inferior", 0, -90},
    };
    Document d = history_.current();
    if (name == "reset") {
        d.view.orbit = {};
        change(d, "reset view");
        return;
    }
    for (const auto &[n, az, el] : views)
        if (n == name) {
            d.view.orbit.azimuth = az;
            d.view.orbit.elevation = el;
            d.view.orbit.pan_right = d.view.orbit.pan_up = 0;
            d.view.auto_view = false;
            change(d, name + " view");
            return;
        }
    throw std::invalid_argument("no standard view '" + name +
                                "' (anterior, posterior, left, right, superior, inferior, reset)");
}

void Workstation::window_level(double width, double level)
{
    if (!(width > 0) || !std::isfinite(width) || !std::isfinite(level))
        throw std::invalid_argument("window-level: the width must be a number > 0 and the level a number");
    view_.window = {width, level};
    view_.window_preset = "manual";
}

void Workstation::window_preset(const std::string &name)
{
    const auto filtered = pipeline_.latest<Stage::Filter>();
    if (name == "auto") {
        if (filtered) {
            const std::optional<double> bg = filtered->background
                                                 ? std::optional<double>(filtered->volume->mapping().physical(
                                                       filtered->background->level))
                                                 : std::nullopt;
            view_.window = auto_window(*filtered->volume, bg);
        }
        view_.window_preset = name;
        return;
    }
    const auto preset = ct_preset(name);
    if (!preset)
        throw std::invalid_argument("no window preset '" + name + "' (auto, brain, bone, lung, soft-tissue, abdomen)");
    view_.window = *preset;
    view_.window_preset = name;
}

void Workstation::move_crosshair(const std::array<int64_t, 3> &ijk)
{
    const auto filtered = pipeline_.latest<Stage::Filter>();
    if (!filtered)
        return;
    const auto &dims = filtered->volume->geometry().dims;
    for (int a = 0; a < 3; ++a)
        view_.crosshair[a] = std::clamp<int64_t>(ijk[a], 0, dims[a] - 1);
}

bool Workstation::pick(double x, double y)
{
    const auto frame = view3d_->latest();
    const auto filtered = pipeline_.latest<Stage::Filter>();
    if (!frame || !filtered || frame->image.width == 0)
        return false;
    const auto &im = frame->image;
    const int64_t px = static_cast<int64_t>(std::floor(x)), py = static_cast<int64_t>(std::floor(y));
    if (px < 0 || py < 0 || px >= im.width || py >= im.height)
        return false;
    const float t = im.depth[static_cast<std::size_t>(py * im.width + px)];
    if (!std::isfinite(t))
        return false;
    // The ray through the pixel's centre, as the ray casters cast it.
    const arbor_camera c = pipeline_.camera();
    const glm::dvec3 pos(c.position[0], c.position[1], c.position[2]);
    const glm::dvec3 f = glm::normalize(glm::dvec3(c.focal_point[0], c.focal_point[1], c.focal_point[2]) - pos);
    glm::dvec3 r = glm::cross(f, glm::dvec3(c.view_up[0], c.view_up[1], c.view_up[2]));
    r = glm::length(r) > 1e-9 ? glm::normalize(r) : glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
    const glm::dvec3 u = glm::cross(r, f);
    const double aspect = static_cast<double>(im.width) / im.height;
    const bool perspective = c.projection == ARBOR_PROJECTION_PERSPECTIVE;
    const double half = perspective ? std::tan(c.view_angle * M_PI / 360.0) : c.parallel_scale;
    const double sx = (2.0 * (px + 0.5) / im.width - 1.0) * aspect * half;
    const double sy = (1.0 - 2.0 * (py + 0.5) / im.height) * half;
    glm::dvec3 origin = pos, direction = f;
    if (perspective)
        direction = glm::normalize(f + sx * r + sy * u);
    else
        origin = pos + sx * r + sy * u;
    const glm::dvec3 p = origin + static_cast<double>(t) * direction;
    // LPS -> voxel: invert position() = origin + D * (spacing * ijk).
    const Geometry &g = filtered->volume->geometry();
    glm::dmat3 d; // column-major: d[c][r]
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            d[col][row] = g.direction[3 * row + col];
    const glm::dvec3 scaled = glm::inverse(d) * (p - glm::dvec3(g.origin[0], g.origin[1], g.origin[2]));
    std::array<int64_t, 3> ijk;
    for (int a = 0; a < 3; ++a)
        ijk[a] = static_cast<int64_t>(std::llround(scaled[a] / g.spacing[a]));
    move_crosshair(ijk);
    // The structure picked is selected, as a click on a slice selects.
    const auto labels = pipeline_.latest<Stage::Labels>();
    if (labels && labels->labels.size() == static_cast<std::size_t>(g.voxel_count())) {
        const auto &c = view_.crosshair;
        const uint32_t label = labels->labels[static_cast<std::size_t>(c[0] + g.dims[0] * (c[1] + g.dims[1] * c[2]))];
        if (label > 0)
            select(static_cast<int32_t>(label));
    }
    return true;
}

void Workstation::set_viewport(uint32_t width, uint32_t height)
{
    width = std::clamp<uint32_t>(width, 16, 8192);
    height = std::clamp<uint32_t>(height, 16, 8192);
    if (viewport_[0] == width && viewport_[1] == height)
        return;
    viewport_ = {width, height};
    try {
        show(history_.current());
    } catch (const std::exception &e) {
        error_ = e.what();
    }
}

void Workstation::save_session(const fs::path &path)
{
    pipeline::write_session(path, pipeline_.document(), catalog());
    say(ARBOR_LOG_INFO, "saved the session " + path.string());
}

void Workstation::screenshot(const fs::path &path)
{
    const auto render = pipeline_.latest<Stage::Render>();
    const auto frame = view3d_->latest();
    if (frame && frame->gpu) {
        // Drawn on the GPU: the frame shown, read back.
        if (!read_back_)
            throw std::runtime_error("screenshot: the 3D view's frame is on the GPU and cannot be read back");
        io::write_image(path, read_back_(*frame->gpu));
    } else if (!render || !pipeline_.is_current(Stage::Render)) {
        // Not yet current: the frame shown (coarse or refined).
        if (!frame)
            throw std::runtime_error("screenshot: the 3D view has no image yet");
        io::write_image(path, frame->image);
    } else {
        io::write_image(path, render->image);
    }
    say(ARBOR_LOG_INFO, "wrote the 3D view " + path.string());
}

void Workstation::export_labels(const fs::path &path)
{
    // The jobs are asked for here; the thread waits for them and writes.
    const auto labels = pipeline_.request(Stage::Labels);
    const auto filtered = pipeline_.request(Stage::Filter);
    writes_.push_back(std::async(std::launch::async, [labels, filtered, path] {
        const auto l = std::static_pointer_cast<const pipeline::StageResult<Stage::Labels>>(labels->wait());
        const auto f = std::static_pointer_cast<const pipeline::StageResult<Stage::Filter>>(filtered->wait());
        io::write_label_map(path, f->volume->geometry(), "arbor labels of " + f->source, l->labels, l->names);
        return "wrote the label map " + path.string();
    }));
}

void Workstation::export_transfer_functions(const fs::path &path)
{
    const auto tf = pipeline_.request(Stage::TransferFunctions);
    const auto filtered = pipeline_.request(Stage::Filter);
    writes_.push_back(std::async(std::launch::async, [tf, filtered, path] {
        const auto t = std::static_pointer_cast<const pipeline::StageResult<Stage::TransferFunctions>>(tf->wait());
        const auto f = std::static_pointer_cast<const pipeline::StageResult<Stage::Filter>>(filtered->wait());
        pipeline::write_transfer_functions(path, *t, f->source);
        return "wrote the transfer functions " + path.string();
    }));
}

void Workstation::harvest_writes(bool wait)
{
    for (auto it = writes_.begin(); it != writes_.end();) {
        if (!wait && it->wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
            ++it;
            continue;
        }
        try {
            say(ARBOR_LOG_INFO, it->get());
        } catch (const std::exception &e) {
            error_ = e.what();
            write_failures_.push_back(e.what());
            say(ARBOR_LOG_ERROR, e.what());
        }
        it = writes_.erase(it);
    }
}

std::vector<std::string> Workstation::finish_writes()
{
    harvest_writes(true);
    return std::exchange(write_failures_, {});
}

void Workstation::volume_changed()
{
    const auto filtered = pipeline_.latest<Stage::Filter>();
    const auto &dims = filtered->volume->geometry().dims;
    for (int a = 0; a < 3; ++a)
        if (view_.crosshair[a] < 0 || view_.crosshair[a] >= dims[a] || filter_revision_ == 0)
            view_.crosshair[a] = dims[a] / 2;
    if (view_.window_preset == "auto" || filter_revision_ == 0) {
        const std::optional<double> bg =
            filtered->background
                ? std::optional<double>(filtered->volume->mapping().physical(filtered->background->level))
                : std::nullopt;
        view_.window = default_window(*filtered->volume, bg);
        view_.window_preset = filtered->volume->mapping().unit == "HU" ? "soft-tissue" : "auto";
    }
    filter_revision_ = filtered->revision;
}

void Workstation::cancel()
{
    cancelled_ = true;
    pipeline_.cancel_all();
    view3d_->cancel();
    say(ARBOR_LOG_INFO, "cancelled; Resume computes again");
}

void Workstation::resume()
{
    cancelled_ = false;
    requested_ = {};
    if (has_input())
        touch_ = view3d_->touch();
}

void Workstation::request_views()
{
    // Once per change of the choices: a stage that failed is not asked again
    // every frame (its error stays on show until the next change).
    const auto revisions = pipeline_.revisions();
    if (revisions == requested_)
        return;
    requested_ = revisions;
    // The slice views need the labels and the legend its wheel; the 3D view
    // asks for the rest itself.
    for (Stage s : {Stage::Labels, Stage::Legend})
        if (s != Stage::Legend || !history_.current().appearance.legend.empty())
            pipeline_.request(s);
}

void Workstation::poll()
{
    harvest_writes(false);
    if (!has_input() || cancelled_)
        return;
    request_views();
    const auto filtered = pipeline_.latest<Stage::Filter>();
    if (filtered && filtered->revision != filter_revision_)
        volume_changed();
    const std::string view_error = view3d_->error();
    if (!view_error.empty() && view_error != error_) {
        error_ = view_error;
        say(ARBOR_LOG_ERROR, view_error);
    }
}

bool Workstation::idle() const
{
    if (!writes_.empty())
        return false;
    if (cancelled_)
        return pipeline_.active_jobs().empty();
    if (!has_input())
        return pipeline_.active_jobs().empty();
    if (!pipeline_.active_jobs().empty())
        return false;
    if (!view3d_->error().empty())
        return true; // nothing more will come until the next change
    const auto frame = view3d_->latest();
    return frame && frame->touch == touch_ && frame->pass != ARBOR_RENDER_PASS_COARSE &&
           pipeline_.is_current(Stage::Render);
}

const std::vector<std::array<float, 3>> &Workstation::colors()
{
    const auto tf = pipeline_.latest<Stage::TransferFunctions>();
    if (!tf) {
        colors_.clear();
        colors_of_ = nullptr;
    } else if (colors_of_ != tf->functions.get()) {
        colors_ = branch_colors(*tf->functions);
        colors_of_ = tf->functions.get();
    }
    return colors_;
}

std::vector<double> Workstation::visibility_shares() const
{
    const auto frame = view3d_->latest();
    std::vector<double> out;
    if (!frame || frame->image.label_visibility.empty())
        return out;
    double total = 0;
    for (double v : frame->image.label_visibility)
        total += v;
    for (double v : frame->image.label_visibility)
        out.push_back(total > 0 ? v / total : 0.0);
    return out;
}

} // namespace arbor::workstation
