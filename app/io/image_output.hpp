// image_output.hpp - writing rendered images: PNG (8-bit sRGB with alpha,
// straight) or OpenEXR (linear-light half-float RGBA, premultiplied as the
// format expects, plus a float Z channel: the depth of the first
// half-opaque hit in mm), chosen by the file's suffix.
#pragma once

#include "core/rendered_image.hpp"

#include <filesystem>

namespace arbor::io {

// ".png" or ".exr"; throws std::invalid_argument for other suffixes and
// std::runtime_error naming the file when writing fails.
void write_image(const std::filesystem::path &path, const RenderedImage &image);

// Fraction of pixels that differ from the top-left one: a blank image gives 0.
double covered_fraction(const RenderedImage &image);

} // namespace arbor::io
