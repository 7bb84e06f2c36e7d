// progressive_view.hpp - how a front (the workstation's viewport) gets
// images while the user drags a slider or orbits: after each touch() a
// coarse frame at once; once no touch has come for `idle` (150 ms), the
// pipeline's full render (balanced and framed for what is now shown),
// then supersample passes while the user stays idle.  A touch cancels
// whatever is being rendered; frames are published with the touch they
// answer, so a front never shows an older answer over a newer one.  The
// pipeline must outlive the view.  A touch does not cancel the stages
// before the render (a new tree after a filter change is computed to the
// end); it cancels the pass and the full render.
//
// With a FrameSurface, a renderer that draws into the host's OpenGL
// context (arbor.renderer-gl/1) draws the coarse, full and supersample
// passes into the surface's canvas with an instance of its own, on this
// view's thread, and a frame carries a texture instead of an image (the
// pipeline's full render still runs first: it balances and frames the
// view).  Other renderers, and previews, give images as without one.
#pragma once

#include "frame_surface.hpp"
#include "pipeline.hpp"
#include "plugin_slot.hpp"

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

namespace arbor::pipeline {

class ProgressiveView {
public:
    struct Options {
        std::chrono::milliseconds idle{150};
        uint32_t supersamples = 4; // passes after the full frame; 0: none
        int worker_nice = 0;       // added to the rendering thread's nice value
        // While the contour tree is computed, a preview from the values
        // (Pipeline::preview_pass) instead of waiting for it.
        bool preview = false;
        std::shared_ptr<FrameSurface> surface = nullptr; // null: frames are images
    };
    struct Frame {
        RenderedImage image;
        arbor_render_pass pass = ARBOR_RENDER_PASS_COARSE;
        uint32_t samples = 0; // SUPERSAMPLE passes blended in
        uint64_t touch = 0;   // the touch it answers
        double seconds = 0;   // to render it
        // Rendered from the values alone while the contour tree was being
        // computed (Pipeline::preview_pass); the topology's frame follows.
        bool preview = false;
        // Drawn into the surface: the texture to show (`image` is then the
        // full render's, for depth and visibility, or empty for a coarse pass).
        std::shared_ptr<const GlFrame> gpu;
    };

    ProgressiveView(Pipeline &pipeline, Options options);
    explicit ProgressiveView(Pipeline &pipeline) : ProgressiveView(pipeline, Options{}) {}
    ~ProgressiveView(); // cancels what is being rendered and waits for it
    ProgressiveView(const ProgressiveView &) = delete;
    ProgressiveView &operator=(const ProgressiveView &) = delete;

    // The document changed (set it on the pipeline first): a coarse frame
    // now, refinement once the user is idle.  Returns the touch's number.
    uint64_t touch();
    // Stops the pass in flight; nothing more is rendered until the next touch.
    void cancel();
    // Called on the rendering thread after each frame is published (a
    // front wakes its event loop with it: glfwPostEmptyEvent); empty: none.
    void on_frame(std::function<void()> callback);
    std::shared_ptr<const Frame> latest() const;
    // The latest frame once it answers touch `touch` at `pass` or better
    // (COARSE < FULL < SUPERSAMPLE with `samples` passes); nullptr on
    // timeout.
    std::shared_ptr<const Frame> wait_for(uint64_t touch, arbor_render_pass pass, uint32_t samples,
                                          std::chrono::milliseconds timeout) const;
    // What went wrong in the last attempt ("" when nothing, and from each
    // touch until its attempt fails).
    std::string error() const;

private:
    void loop();
    void publish(std::shared_ptr<const Frame> frame);
    // The pass into the surface's canvas, when there is a surface and the
    // document's renderer draws into it; false (nothing drawn) otherwise.
    bool draw_gl(Frame &frame, const FramePass &pass, std::stop_token stop);
    void release_gl_renderers();

    Pipeline &pipeline_;
    Options options_;
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    uint64_t touches_ = 0;
    uint64_t halted_ = 0; // the touch cancel() stopped (touches_ == halted_: rest)
    std::chrono::steady_clock::time_point last_touch_;
    std::stop_source rendering_; // of the pass in flight
    bool quit_ = false;
    std::shared_ptr<const Frame> latest_;
    std::function<void()> on_frame_;
    std::string error_;
    // The renderers that drew into the surface (this thread's own), and
    // whether the canvas holds the full pass a supersample pass refines.
    PluginSlot gl_renderers_;
    std::map<std::string, bool> draws_gl_; // per renderer id: does it offer arbor.renderer-gl/1?
    std::vector<PluginSetting> drew_gl_;
    bool canvas_full_ = false;
    std::thread worker_;
};

} // namespace arbor::pipeline
