// gl_objects.hpp - OpenGL names that delete themselves.  Created and
// destroyed on the GL thread only.
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <utility>

namespace arbor::glraycast {

template <void (*Delete)(GLuint)> class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    GlName(GlName &&o) noexcept : name_(std::exchange(o.name_, 0)) {}
    GlName &operator=(GlName &&o) noexcept
    {
        if (this != &o) {
            reset();
            name_ = std::exchange(o.name_, 0);
        }
        return *this;
    }
    ~GlName() { reset(); }
    void reset()
    {
        if (name_)
            Delete(name_);
        name_ = 0;
    }
    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }

private:
    GLuint name_ = 0;
};

namespace detail {
inline void delete_texture(GLuint n) { glDeleteTextures(1, &n); }
inline void delete_framebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void delete_vertex_array(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void delete_program(GLuint n) { glDeleteProgram(n); }
} // namespace detail

using Texture = GlName<detail::delete_texture>;
using Framebuffer = GlName<detail::delete_framebuffer>;
using VertexArray = GlName<detail::delete_vertex_array>;
using Program = GlName<detail::delete_program>;

inline Texture make_texture()
{
    GLuint n = 0;
    glGenTextures(1, &n);
    return Texture(n);
}

// Throws std::runtime_error naming `what` when GL recorded an error
// (GL_OUT_OF_MEMORY above all).
void check_gl(const char *what);

} // namespace arbor::glraycast
