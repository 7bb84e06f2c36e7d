#include "progressive_view.hpp"

#include "core/cancelled.hpp"
#include "core/stopwatch.hpp"
#include "core/thread_priority.hpp"
#include "host/host_services.hpp"

#include <algorithm>

namespace arbor::pipeline {

namespace {

// COARSE < FULL < SUPERSAMPLE 1 < SUPERSAMPLE 2 ...
uint32_t rank(arbor_render_pass pass, uint32_t samples)
{
    return pass == ARBOR_RENDER_PASS_COARSE ? 0 : pass == ARBOR_RENDER_PASS_FULL ? 1 : 1 + samples;
}

} // namespace

ProgressiveView::ProgressiveView(Pipeline &pipeline, Options options)
    : pipeline_(pipeline), options_(std::move(options)), gl_renderers_(pipeline.catalog()), worker_([this] { loop(); })
{
}

ProgressiveView::~ProgressiveView()
{
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        rendering_.request_stop();
    }
    changed_.notify_all();
    worker_.join();
}

uint64_t ProgressiveView::touch()
{
    std::lock_guard lock(mutex_);
    last_touch_ = std::chrono::steady_clock::now();
    rendering_.request_stop(); // the pass in flight answers an older touch
    error_.clear();            // a new attempt: the last one's failure is no longer the news
    const uint64_t n = ++touches_;
    changed_.notify_all();
    return n;
}

void ProgressiveView::cancel()
{
    std::lock_guard lock(mutex_);
    halted_ = touches_;
    rendering_.request_stop();
    changed_.notify_all();
}

std::shared_ptr<const ProgressiveView::Frame> ProgressiveView::latest() const
{
    std::lock_guard lock(mutex_);
    return latest_;
}

std::string ProgressiveView::error() const
{
    std::lock_guard lock(mutex_);
    return error_;
}

std::shared_ptr<const ProgressiveView::Frame> ProgressiveView::wait_for(uint64_t touch, arbor_render_pass pass,
                                                                        uint32_t samples,
                                                                        std::chrono::milliseconds timeout) const
{
    std::unique_lock lock(mutex_);
    const bool ok = changed_.wait_for(lock, timeout, [&] {
        return latest_ && latest_->touch >= touch &&
               (latest_->touch > touch || rank(latest_->pass, latest_->samples) >= rank(pass, samples));
    });
    return ok ? latest_ : nullptr;
}

void ProgressiveView::on_frame(std::function<void()> callback)
{
    std::lock_guard lock(mutex_);
    on_frame_ = std::move(callback);
}

void ProgressiveView::publish(std::shared_ptr<const Frame> frame)
{
    std::function<void()> tell;
    {
        std::lock_guard lock(mutex_);
        if (frame->touch != touches_)
            return; // answered a touch that has been overtaken
        latest_ = std::move(frame);
        error_.clear();
        tell = on_frame_;
    }
    changed_.notify_all();
    if (tell)
        tell();
}

bool ProgressiveView::draw_gl(Frame &frame, const FramePass &pass, std::stop_token stop)
{
    if (!options_.surface)
        return false;
    const PluginSetting setting = pipeline_.document().view.renderer;
    auto known = draws_gl_.find(setting.id);
    if (known == draws_gl_.end())
        known = draws_gl_.emplace(setting.id, renders_into_gl(*gl_renderers_.lease(setting, nullptr))).first;
    if (!known->second)
        return false;
    const std::unique_ptr<PassScene> p = pipeline_.pass_scene(stop);
    PluginSlot::Lease renderer = gl_renderers_.lease(p->renderer, nullptr);
    if (std::none_of(drew_gl_.begin(), drew_gl_.end(), [&](const PluginSetting &d) { return d.id == p->renderer.id; }))
        drew_gl_.push_back(p->renderer);
    if (pass.pass == ARBOR_RENDER_PASS_SUPERSAMPLE && !canvas_full_)
        return false; // the canvas does not hold the full pass to refine
    arbor_render_request request = p->scene->request;
    // Shown as drawn: the background composited, as an image's is when a
    // front shows it.
    request.background[3] = 1.0f;
    canvas_full_ = false;
    try {
        render_gl(*renderer, request, options_.surface->canvas(p->width, p->height), {}, pass, nullptr, stop);
    } catch (const Cancelled &) {
        throw;
    } catch (const std::exception &e) {
        // Its offscreen path may still work (a context it cannot use, a
        // device out of memory): images from now on, and said why.
        known->second = false;
        log_message(ARBOR_LOG_WARNING, p->renderer.id,
                    std::string("the 3D view's frames come back through the CPU: ") + e.what());
        return false;
    }
    canvas_full_ = pass.pass != ARBOR_RENDER_PASS_COARSE;
    frame.gpu = options_.surface->snapshot();
    return true;
}

// What the renderers made in the surface's context, deleted there (it is
// current on this thread) before the instances go.
void ProgressiveView::release_gl_renderers()
{
    for (const PluginSetting &setting : drew_gl_) {
        try {
            release_gl(*gl_renderers_.lease(setting, nullptr));
        } catch (const std::exception &) {
            // A renderer that cannot release leaks its objects into a context that ends with the view.
        }
    }
    drew_gl_.clear();
}

void ProgressiveView::loop()
{
    lower_thread_priority(options_.worker_nice);
    struct Surface { // current on this thread while the loop runs
        FrameSurface *surface;
        ProgressiveView &view;
        ~Surface()
        {
            if (!surface)
                return;
            view.release_gl_renderers();
            surface->release_current();
        }
    } current{options_.surface.get(), *this};
    if (options_.surface)
        options_.surface->make_current();
    uint64_t done = 0;            // the touch the latest frame answers
    uint32_t refinement = 0;      // passes after the coarse one for it: 1 full, then supersamples
    RenderedImage image;
    for (;;) {
        std::stop_token stop;
        uint64_t touch = 0;
        bool coarse = false;
        {
            std::unique_lock lock(mutex_);
            for (;;) {
                if (quit_)
                    return;
                if (touches_ == halted_ && touches_ > 0) {
                    changed_.wait(lock); // cancelled: rest until the next touch
                    continue;
                }
                if (touches_ > done) {
                    coarse = true;
                    break;
                }
                const auto ready = last_touch_ + options_.idle;
                if (touches_ > 0 && refinement < 1 + options_.supersamples) {
                    if (std::chrono::steady_clock::now() >= ready)
                        break;
                    changed_.wait_until(lock, ready);
                } else {
                    changed_.wait(lock);
                }
            }
            touch = touches_;
            rendering_ = std::stop_source();
            stop = rendering_.get_token();
        }
        auto frame = std::make_shared<Frame>();
        frame->touch = touch;
        Stopwatch watch;
        try {
            if (coarse) {
                frame->pass = ARBOR_RENDER_PASS_COARSE;
                // While the tree is computed (a new scan or filter), the
                // volume from its values at once; the full render after it
                // waits for the tree.
                frame->preview = options_.preview && !pipeline_.is_current(Stage::ContourTree);
                if (frame->preview)
                    pipeline_.preview_pass(image, {ARBOR_RENDER_PASS_COARSE, 0, 0}, stop);
                else if (!draw_gl(*frame, {ARBOR_RENDER_PASS_COARSE, 0, 0}, stop))
                    pipeline_.render_pass(image, {ARBOR_RENDER_PASS_COARSE, 0, 0}, stop);
                done = touch;
                refinement = 0;
            } else if (refinement == 0) {
                // The pipeline's render: balanced and framed for what is shown.
                const std::shared_ptr<Job> job = pipeline_.request(Stage::Render);
                std::stop_callback cancel(stop, [&] { job->cancel(); });
                const auto render = std::static_pointer_cast<const RenderResult>(job->wait(stop));
                image = render->image;
                frame->pass = ARBOR_RENDER_PASS_FULL;
                // Drawn again into the surface: balanced and framed as the render was.
                draw_gl(*frame, {ARBOR_RENDER_PASS_FULL, 0, 0}, stop);
                refinement = 1;
            } else {
                frame->pass = ARBOR_RENDER_PASS_SUPERSAMPLE;
                frame->samples = refinement;
                if (!draw_gl(*frame, {ARBOR_RENDER_PASS_SUPERSAMPLE, refinement, 0}, stop))
                    pipeline_.render_pass(image, {ARBOR_RENDER_PASS_SUPERSAMPLE, refinement, 0}, stop);
                ++refinement;
            }
        } catch (const Cancelled &) {
            continue; // a newer touch, or the end
        } catch (const std::exception &e) {
            std::lock_guard lock(mutex_);
            error_ = e.what();
            done = touch;
            refinement = 1 + options_.supersamples; // nothing more to try until the next touch
            continue;
        }
        frame->seconds = watch.lap();
        // A GPU frame of the full render keeps its image too (same view):
        // depth for picking, visibility.  A coarse one has none.
        if (!frame->gpu || frame->pass != ARBOR_RENDER_PASS_COARSE)
            frame->image = image;
        publish(std::move(frame));
    }
}

} // namespace arbor::pipeline
