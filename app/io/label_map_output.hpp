// label_map_output.hpp - a voxel -> label map as NRRD, with a colour table
// beside it in 3D Slicer's format (".ctbl": "label name R G B A" lines), so
// the labels open in Slicer as a coloured label map.
#pragma once

#include "core/volume.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace arbor::io {

// The colour table written next to `labels_path`: its .nrrd/.nhdr suffix
// replaced by .ctbl (or .ctbl appended).
std::filesystem::path color_table_path(const std::filesystem::path &labels_path);

// Writes labels (uint16, or uint32 for more than 65535 names) with the
// geometry of the labelled volume, and the colour table naming every label:
// names[k] for label k (no spaces; they are replaced).  Throws
// std::runtime_error naming the file on failure.
void write_label_map(const std::filesystem::path &path, const Geometry &geometry, const std::string &content,
                     std::span<const uint32_t> labels, const std::vector<std::string> &names);

} // namespace arbor::io
