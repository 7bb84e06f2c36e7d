// framing.hpp - a camera that frames what is visible, not the grid's box:
// a scan's grid holds much empty air (and a phantom's a margin), so the
// orbit camera, which fits the whole grid, leaves the body small.  From a
// preview rendered with the orbit camera, the box of the pixels where
// something is seen gives how far to pan and zoom so that the content fills
// `fill` of the shorter image side (and fits the longer one).
#pragma once

#include "host/rendering.hpp"

#include <arbor/renderer.h>

#include <optional>

namespace arbor::pipeline {

struct Framing {
    arbor_camera camera{};
    double scale = 1.0;            // how much the content was enlarged
    double content_fraction = 0.0; // of the shorter side the content spanned before
};

// nullopt when nothing is seen in the preview.  `preview`: rendered with
// `camera` at the final image's aspect ratio.
std::optional<Framing> frame_content(const arbor_camera &camera, const RenderedImage &preview, uint32_t width,
                                     uint32_t height, double fill = 0.85);

} // namespace arbor::pipeline
