// legend_png.hpp - a depictor's legend (the relation wheel), drawn by the
// plugin as premultiplied RGBA floats, written as a PNG over white.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace arbor::io {

// `rgba`: size x size pixels, row 0 at the top.  Throws std::runtime_error
// naming the file on failure.
void write_legend_png(const std::filesystem::path &path, uint32_t size, const std::vector<float> &rgba);

} // namespace arbor::io
