#include "window_surface.hpp"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace arbor::workstation {

namespace {

// RGBA16F: supersample passes blend into the canvas without 8-bit rounding.
GLuint make_texture(uint32_t width, uint32_t height)
{
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, static_cast<GLsizei>(width), static_cast<GLsizei>(height), 0, GL_RGBA,
                 GL_FLOAT, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    if (glGetError() == GL_OUT_OF_MEMORY)
        throw std::runtime_error("the graphics device has no memory for a frame of the 3D view");
    return t;
}

} // namespace

WindowSurface::WindowSurface(GLFWwindow *shown)
{
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(1, 1, "arbor renderer", nullptr, shown);
    glfwDefaultWindowHints();
    if (!window_)
        throw std::runtime_error("no OpenGL context can share textures with the window");
}

WindowSurface::~WindowSurface()
{
    for (const GLuint t : textures_)
        glDeleteTextures(1, &t);
    glfwDestroyWindow(window_);
}

void WindowSurface::make_current()
{
    glfwMakeContextCurrent(window_);
    GLuint f[2] = {0, 0};
    glGenFramebuffers(2, f);
    read_fbo_ = f[0];
    draw_fbo_ = f[1];
}

void WindowSurface::release_current()
{
    const GLuint f[2] = {read_fbo_, draw_fbo_};
    glDeleteFramebuffers(2, f);
    read_fbo_ = draw_fbo_ = 0;
    glFinish();
    glfwMakeContextCurrent(nullptr);
}

GlFrame WindowSurface::canvas(uint32_t width, uint32_t height)
{
    if (canvas_.texture == 0 || canvas_.width != width || canvas_.height != height) {
        const GLuint t = make_texture(width, height);
        {
            std::lock_guard lock(textures_mutex_);
            textures_.push_back(t);
        }
        if (canvas_.texture) { // the old canvas serves as a copy of its size, or goes
            std::lock_guard lock(pool_->mutex);
            pool_->idle.push_back(canvas_);
        }
        canvas_ = {t, width, height};
    }
    return canvas_;
}

std::shared_ptr<const GlFrame> WindowSurface::snapshot()
{
    GlFrame copy;
    {
        std::lock_guard lock(pool_->mutex);
        auto &idle = pool_->idle;
        for (auto it = idle.begin(); it != idle.end(); ++it)
            if (it->width == canvas_.width && it->height == canvas_.height) {
                copy = *it;
                idle.erase(it);
                break;
            }
        // Copies of other sizes are of no more use: the view changed size.
        for (const GlFrame &old : idle) {
            glDeleteTextures(1, &old.texture);
            std::lock_guard t(textures_mutex_);
            std::erase(textures_, old.texture);
        }
        idle.clear();
    }
    if (copy.texture == 0) {
        copy = {make_texture(canvas_.width, canvas_.height), canvas_.width, canvas_.height};
        std::lock_guard lock(textures_mutex_);
        textures_.push_back(copy.texture);
    }
    const GLint w = static_cast<GLint>(canvas_.width), h = static_cast<GLint>(canvas_.height);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo_);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, canvas_.texture, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, draw_fbo_);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, copy.texture, 0);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    // The window's context shows it next: every command on it done first.
    glFinish();
    const std::weak_ptr<Pool> pool = pool_;
    return std::shared_ptr<const GlFrame>(new GlFrame(copy), [pool](const GlFrame *frame) {
        if (const auto p = pool.lock()) {
            std::lock_guard lock(p->mutex);
            p->idle.push_back(*frame); // the rendering thread reuses it; no GL call here
        }
        delete frame;
    });
}

RenderedImage read_frame(const GlFrame &frame)
{
    RenderedImage image;
    image.width = frame.width;
    image.height = frame.height;
    image.rgba.assign(std::size_t{frame.width} * frame.height * 4, 0.0f);
    GLint bound = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glBindTexture(GL_TEXTURE_2D, frame.texture);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, image.rgba.data());
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
    if (glGetError() != GL_NO_ERROR)
        throw std::runtime_error("the 3D view's frame cannot be read back from the GPU");
    return image;
}

} // namespace arbor::workstation
