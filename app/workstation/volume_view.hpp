// volume_view.hpp - the 3D view: the progressive view's latest frame as a
// texture, mouse as in 3D Slicer (left drag rotates, middle or Shift+left
// drag pans, right drag or the wheel zooms, a left click picks the first
// opaque point and moves the crosshair there), keys for the six standard
// views (A, P, L, R, S, I; Home resets), an orientation marker and the
// patient directions at the view's edges.  What the frame is: coarse while
// the user drags, refined once still, named in the view's corner.  A frame
// a renderer drew on the GPU (the workstation's WindowSurface) is shown
// from its texture as it is; an image is uploaded.
#pragma once

#include "gl_texture.hpp"

#include "pipeline/progressive_view.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace arbor::workstation {

class Workstation;

class VolumeView {
public:
    // Draws into the current ImGui window's remaining space.
    void draw(Workstation &workstation);
    // Texture and pixel memory for frames up to `width` x `height`, made
    // now, before any job runs (see SliceView::reserve).  Needs the
    // window's OpenGL context current.
    void reserve(uint32_t width, uint32_t height);
    // Lets go of the GPU frame it shows (before the surface goes).
    void let_go() { drawn_.reset(); }

private:
    GlTexture texture_;
    const void *shown_ = nullptr; // the frame uploaded last
    // The GPU frame shown, held until the window has drawn it (its texture
    // is reused for a later frame once no one holds it).
    std::shared_ptr<const pipeline::ProgressiveView::Frame> drawn_;
    std::vector<uint8_t> rgba_;   // its 8-bit pixels (the memory reused frame after frame)
    bool dragging_ = false;
};

} // namespace arbor::workstation
