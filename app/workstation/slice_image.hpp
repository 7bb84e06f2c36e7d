// slice_image.hpp - one slice view's picture: the grey values through the
// window, with the branch labels over them in their colours (the selected
// branch stronger, hidden branches left out).  Plain CPU code on the
// pipeline's results, so it is tested without a window.
#pragma once

#include "slice_geometry.hpp"
#include "window_level.hpp"

#include "core/volume.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace arbor::workstation {

struct LabelOverlay {
    std::span<const uint32_t> labels;                      // per voxel; empty: no overlay
    const std::vector<std::array<float, 3>> *colors = nullptr; // per label, sRGB [0, 1]
    double opacity = 0.35;
    std::optional<uint32_t> selected;
    const std::vector<bool> *hidden = nullptr; // per label; may be null
};

struct SliceImage {
    int64_t width = 0, height = 0;
    std::vector<uint8_t> rgba; // row 0 at the top, opaque
};

// Into `out`, reusing its memory: the UI thread allocates nothing new per
// slice (a fresh allocation's page faults can wait behind a job's mmap).
void slice_image(const Volume &volume, const SliceGeometry &geometry, int64_t slice, const WindowLevel &window,
                 const LabelOverlay &overlay, SliceImage &out);
SliceImage slice_image(const Volume &volume, const SliceGeometry &geometry, int64_t slice, const WindowLevel &window,
                       const LabelOverlay &overlay = {});

} // namespace arbor::workstation
