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
//
// Per label (transfer function), its visibility: the opacity its samples
// contributed to the image, summed over rays (T * alpha); empty when the
// renderer does not measure it.
struct RenderedImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba, depth;
    std::vector<double> label_visibility;
};

} // namespace arbor
