// frame_surface.hpp - where a front wants its 3D frames drawn on the GPU,
// for renderers that draw into a host's OpenGL context
// (arbor.renderer-gl/1): a context that shares textures with the one that
// shows the frames, made current on the view's rendering thread; a canvas
// texture the passes draw into (a supersample pass blends into what it
// holds); and finished copies of it to show.  The pipeline makes no GL call
// of its own: the workstation implements this with a hidden GLFW window.
#pragma once

#include "host/rendering.hpp"

#include <memory>

namespace arbor::pipeline {

class FrameSurface {
public:
    virtual ~FrameSurface() = default;
    // On the rendering thread, before its first pass and after its last.
    virtual void make_current() = 0;
    virtual void release_current() = 0;
    // The canvas, width x height (made anew when the size changes).
    virtual GlFrame canvas(uint32_t width, uint32_t height) = 0;
    // A copy of the canvas with the GPU's work on it finished, for another
    // context to show; its texture is reused once the last holder lets go.
    virtual std::shared_ptr<const GlFrame> snapshot() = 0;
};

} // namespace arbor::pipeline
