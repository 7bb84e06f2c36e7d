// contact_sheet.hpp - the images of a sweep side by side, each captioned
// with what made it different ("Q 120, hat"), in one PNG: how a comparison
// study is looked at first.
#pragma once

#include "core/rendered_image.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace arbor::io {

struct ContactSheetTile {
    const RenderedImage *image;
    std::string caption;
};

// Tiles in rows of ceil(sqrt(n)), each image scaled to at most `tile` pixels
// on its longer side and composited over dark grey, its caption beneath, a
// title line on top.  Throws std::runtime_error naming the file on failure.
void write_contact_sheet(const std::filesystem::path &path, const std::string &title,
                         const std::vector<ContactSheetTile> &tiles, int tile = 320);

} // namespace arbor::io
