// window_surface.hpp - the 3D view's frames drawn on the GPU by renderers
// that draw into the host's OpenGL context (arbor.renderer-gl/1): a hidden
// GLFW window whose context shares textures with the workstation's window,
// current on the progressive view's thread; its canvas and the finished
// copies the window shows, without a read back.
#pragma once

#include "pipeline/frame_surface.hpp"

#include <memory>
#include <mutex>
#include <vector>

struct GLFWwindow;

namespace arbor::workstation {

class WindowSurface final : public pipeline::FrameSurface {
public:
    // On the main thread, `shown` current: throws std::runtime_error when
    // no context sharing with it can be made.
    explicit WindowSurface(GLFWwindow *shown);
    // On the main thread, `shown` current, after the rendering thread let go.
    ~WindowSurface() override;
    WindowSurface(const WindowSurface &) = delete;
    WindowSurface &operator=(const WindowSurface &) = delete;

    void make_current() override;
    void release_current() override;
    GlFrame canvas(uint32_t width, uint32_t height) override;
    std::shared_ptr<const GlFrame> snapshot() override;

private:
    struct Pool {
        std::mutex mutex;
        std::vector<GlFrame> idle; // copies no frame holds any more
    };

    GLFWwindow *window_ = nullptr;
    GlFrame canvas_;
    unsigned read_fbo_ = 0, draw_fbo_ = 0; // the rendering context's own
    std::vector<unsigned> textures_;       // every texture made, deleted at the end
    std::mutex textures_mutex_;
    std::shared_ptr<Pool> pool_ = std::make_shared<Pool>();
};

// A frame's texels, row 0 first, read with a context of the share group
// current (the window's): a screenshot of what the 3D view shows.
RenderedImage read_frame(const GlFrame &frame);

} // namespace arbor::workstation
