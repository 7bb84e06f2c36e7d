// color_table.hpp - reading a 3D Slicer colour table (".ctbl": lines
// "label name R G B A", '#' comments), the names and colours of a label
// map's structures.
#pragma once

#include "label_colors.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace arbor::io {

struct ColorTableEntry {
    std::string name;
    Rgb8 colour{};
};

// Throws std::runtime_error naming the file and line when it cannot be read.
std::map<uint32_t, ColorTableEntry> read_color_table(const std::filesystem::path &path);

} // namespace arbor::io
