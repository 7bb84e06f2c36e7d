// gl_texture.hpp - a 2D RGBA8 texture the views draw into ImGui: the 3D
// view's latest frame, a slice, the relation wheel.  Needs a current OpenGL
// context (the window's); uploads replace the texture's contents
// (glTexSubImage2D into the storage it has when the image fits).
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
    // Storage for images up to `width` x `height`, made (and its memory
    // touched) now: a view that reserves before any job runs later uploads
    // without allocating, whose page faults wait on the jobs' own mappings
    // (the first slice images cost a frame 40-50 ms so while the tree ran).
    // Its image is then one black pixel: drawing it makes a software OpenGL
    // compile its shader at startup rather than while the first jobs run.
    void reserve(int64_t width, int64_t height, bool smooth);
    bool empty() const { return id_ == 0; }
    // For ImGui::Image: the texture and the corner of its storage the last
    // image fills (the storage may be larger).
    void *imgui_id() const { return reinterpret_cast<void *>(static_cast<intptr_t>(id_)); }
    float u_max() const { return storage_width_ > 0 ? static_cast<float>(width_) / static_cast<float>(storage_width_) : 1; }
    float v_max() const { return storage_height_ > 0 ? static_cast<float>(height_) / static_cast<float>(storage_height_) : 1; }
    int64_t width() const { return width_; }
    int64_t height() const { return height_; }

private:
    void allocate(const uint8_t *rgba, int64_t width, int64_t height, bool smooth);

    unsigned id_ = 0;
    int64_t width_ = 0, height_ = 0;                 // the last image
    int64_t storage_width_ = 0, storage_height_ = 0; // the texture's storage
    bool smooth_ = false;
};

// Premultiplied sRGB float RGBA (a rendered image) over an opaque
// background, as 8-bit RGBA into `out` (resized; its memory reused).
void to_rgba8(const std::vector<float> &rgba, const float background[3], std::vector<uint8_t> &out);

} // namespace arbor::workstation
