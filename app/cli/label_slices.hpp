// label_slices.hpp - label maps side by side on the central axial slice (the
// middle k of the volume), each over the grey-scale intensities, with the
// intensities alone first: what a comparison of simplifiers looks like at a
// glance.
#pragma once

#include "core/volume.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace arbor::cli {

struct LabelPanel {
    std::string title;
    const std::vector<uint32_t> *labels; // voxel -> label, the volume's size
};

// Throws std::runtime_error naming the file when it cannot be written.
void write_label_slices(const std::filesystem::path &path, const Volume &volume,
                        const std::vector<LabelPanel> &panels);

} // namespace arbor::cli
