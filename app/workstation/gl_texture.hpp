// gl_texture.hpp - a 2D RGBA8 texture the views draw into ImGui: the 3D
// view's latest frame, a slice, the relation wheel.  Needs a current OpenGL
// context (the window's); uploads replace the texture's contents
// (glTexSubImage2D when the size stays).
#pragma once

#include <cstdint>
#include <vector>

namespace arbor::workstation {

class GlTexture {
public:
    GlTexture() = default;
    ~GlTexture();
    GlTexture(const GlTexture &) = delete;
    GlTexture &operator=(const GlTexture &) = delete;

    // `rgba`: width x height x 4 bytes, row 0 at the top.  `smooth`: linear
    // filtering (the 3D view) rather than nearest (slices: voxels stay sharp).
    void upload(const uint8_t *rgba, int64_t width, int64_t height, bool smooth);
    bool empty() const { return id_ == 0; }
    // For ImGui::Image.
    void *imgui_id() const { return reinterpret_cast<void *>(static_cast<intptr_t>(id_)); }
    int64_t width() const { return width_; }
    int64_t height() const { return height_; }

private:
    unsigned id_ = 0;
    int64_t width_ = 0, height_ = 0;
    bool smooth_ = false;
};

// Premultiplied sRGB float RGBA (a rendered image) over an opaque
// background, as 8-bit RGBA.
std::vector<uint8_t> to_rgba8(const std::vector<float> &rgba, const float background[3]);

} // namespace arbor::workstation
