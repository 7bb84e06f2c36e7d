// volume_import.hpp - opening a volume through the importer plugins.
//
// The importer is either named by the user or chosen by probing every
// importer with the file's first bytes (highest confidence wins; suffix
// matches break ties).  The host checks the header the importer returns
// (volume_header.hpp) before it allocates voxel memory, then lets the
// importer fill it.
#pragma once

#include "plugin_registry.hpp"

#include "../core/volume.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace arbor {

struct ImporterChoice {
    std::string id;
    int32_t confidence = 0;
};

// Importers ranked for `path`, best first, confidence > 0 only.
std::vector<ImporterChoice> rank_importers(const PluginRegistry &registry,
                                           const std::filesystem::path &path);

// Picks the importer for `path`; throws std::runtime_error listing what was
// tried when no importer recognises it.
std::string choose_importer(const PluginRegistry &registry, const std::filesystem::path &path);

// What the caller says of a header before the voxels are allocated: "" to
// go on, otherwise why not (the run this volume is for would not fit).
using HeaderAdmission = std::function<std::string(const arbor_volume &header)>;

// Reads the volume with an instance whose parameters are already set.
// Throws PluginError / std::runtime_error with a message naming the file;
// `admit` sees the checked header before anything is allocated.
Volume import_volume(PluginInstance &importer, const std::filesystem::path &path,
                     ProgressSink *progress, uint64_t max_bytes, std::stop_token stop = {},
                     const HeaderAdmission &admit = {});

} // namespace arbor
