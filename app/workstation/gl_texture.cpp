#include "gl_texture.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

namespace arbor::workstation {

GlTexture::~GlTexture()
{
    if (id_)
        glDeleteTextures(1, &id_);
}

void GlTexture::allocate(const uint8_t *rgba, int64_t width, int64_t height, bool smooth)
{
    if (!id_)
        glGenTextures(1, &id_);
    glBindTexture(GL_TEXTURE_2D, id_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const GLint filter = smooth ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, static_cast<GLsizei>(width), static_cast<GLsizei>(height), 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, rgba);
    glBindTexture(GL_TEXTURE_2D, 0);
    storage_width_ = width;
    storage_height_ = height;
    smooth_ = smooth;
}

void GlTexture::reserve(int64_t width, int64_t height, bool smooth)
{
    if (width <= storage_width_ && height <= storage_height_ && smooth == smooth_ && id_)
        return;
    // Zeros, so the driver writes (and so maps) every page now.
    const std::vector<uint8_t> zeros(static_cast<std::size_t>(width * height * 4), 0);
    allocate(zeros.data(), width, height, smooth);
    const uint8_t black[4] = {0, 0, 0, 255};
    upload(black, 1, 1, smooth);
}

void GlTexture::upload(const uint8_t *rgba, int64_t width, int64_t height, bool smooth)
{
    if (width <= 0 || height <= 0)
        return;
    if (!id_ || width > storage_width_ || height > storage_height_ || smooth != smooth_) {
        allocate(rgba, width, height, smooth);
    } else {
        glBindTexture(GL_TEXTURE_2D, id_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height), GL_RGBA,
                        GL_UNSIGNED_BYTE, rgba);
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    width_ = width;
    height_ = height;
}

void to_rgba8(const std::vector<float> &rgba, const float background[3], std::vector<uint8_t> &out)
{
    out.resize(rgba.size());
    for (std::size_t p = 0; p + 3 < rgba.size(); p += 4) {
        const float a = std::clamp(rgba[p + 3], 0.0f, 1.0f);
        for (int k = 0; k < 3; ++k) {
            const float c = rgba[p + k] + (1 - a) * background[k];
            // Rounded by adding a half (c is clamped, so never negative):
            // lround, a library call per channel, made this 14 ms a frame.
            out[p + k] = static_cast<uint8_t>(std::clamp(c, 0.0f, 1.0f) * 255.0f + 0.5f);
        }
        out[p + 3] = 255;
    }
}

} // namespace arbor::workstation
