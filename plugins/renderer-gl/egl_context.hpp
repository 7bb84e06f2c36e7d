// egl_context.hpp - an OpenGL 3.3 core context without a window or an X
// server: EGL on a graphics device (headless GPUs), else Mesa's surfaceless
// platform.  Rendering goes to framebuffer objects.
#pragma once

#include <string>

namespace arbor::glraycast {

class EglContext {
public:
    // Throws std::runtime_error saying what is missing when no context can
    // be made.  Hardware devices are preferred to software rasterisers.
    EglContext();
    ~EglContext();
    EglContext(const EglContext &) = delete;
    EglContext &operator=(const EglContext &) = delete;

    // Makes the context current on the calling thread (or releases it).
    void make_current();
    void release();

    // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6".
    const std::string &description() const { return description_; }
    // Mesa llvmpipe, softpipe, SwiftShader...: graphics emulated on the CPU.
    bool software() const { return software_; }

private:
    bool open(void *display, std::string &why);

    void *display_ = nullptr, *context_ = nullptr;
    std::string description_;
    bool software_ = false;
};

// True for the GL_RENDERER strings of software rasterisers.
bool is_software_renderer(const std::string &renderer);

} // namespace arbor::glraycast
