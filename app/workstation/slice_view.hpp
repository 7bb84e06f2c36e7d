// slice_view.hpp - one of the three slice views (axial, coronal, sagittal)
// in patient orientation (slice_geometry.hpp): the filtered volume through
// the window, the branch labels over it, the crosshair linking the three.
// Wheel scrolls slices, left click moves the crosshair and selects the
// branch under it, right drag changes window/level (as in Slicer and Horos);
// the slice's position in mm and the value under the cursor (HU on CT) are
// written in its corner.
#pragma once

#include "gl_texture.hpp"
#include "slice_geometry.hpp"
#include "slice_image.hpp"
#include "window_level.hpp"

#include "host/tf_generation.hpp"

#include <array>
#include <memory>
#include <cstdint>
#include <optional>
#include <vector>

namespace arbor::workstation {

class Workstation;

class SliceView {
public:
    explicit SliceView(SliceOrientation orientation) : orientation_(orientation) {}
    void draw(Workstation &workstation);
    // Texture and image memory for slices up to 1024 pixels a side, made
    // (and touched) now: called before the first job starts, so the first
    // slices upload without page faults that would wait on the jobs' own
    // mappings (they cost a frame 40-55 ms while the tree was computed).
    // Needs the window's OpenGL context current.
    void reserve();
    SliceOrientation orientation() const { return orientation_; }

private:
    struct Key {
        uint64_t volume = 0, labels = 0;
        int64_t slice = -1;
        double width = 0, level = 0, opacity = 0;
        bool overlay = false;
        std::optional<uint32_t> selected;
        std::vector<bool> hidden;
        const void *colors = nullptr;
        bool operator==(const Key &) const = default;
    };
    SliceOrientation orientation_;
    GlTexture texture_;
    SliceImage image_; // reused
    std::vector<std::array<float, 3>> overlay_colors_; // of overlay_of_
    std::shared_ptr<const TransferFunctions> overlay_of_;
    Key shown_;
};

} // namespace arbor::workstation
