// rendered_image.hpp - an image as renderers produce it, in host memory:
// what the rendering code hands to the image writers, kept here so that
// writing images needs no plugin host.
#pragma once

#include <cstdint>
#include <vector>

namespace arbor {

// RGBA floats, premultiplied, display-encoded sRGB, row 0 at the top, and
// the distance in mm at which each pixel's ray became half opaque (+inf
// where it never did).
struct RenderedImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba, depth;
};

} // namespace arbor
