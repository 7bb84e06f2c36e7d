// volume_input.hpp - the volume a command works on: a file or folder read
// through an importer plugin, or a built-in phantom (`--phantom head`), the
// default data that needs no files.  Importer parameters become flags.
#pragma once

#include "cli_context.hpp"
#include "plugin_options.hpp"

#include "core/volume.hpp"

#include <memory>
#include <string>
#include <vector>

namespace arbor::cli {

struct LoadedVolume {
    Volume volume;
    std::string source;      // the path, or "phantom:head"
    std::string importer_id; // empty for phantoms
    std::string importer_version;
};

class VolumeInput {
public:
    // Adds the positional <volume>, --phantom*, --importer and importer flags.
    void add_to(CLI::App &command, Context &context);
    LoadedVolume load();

private:
    Context *context_ = nullptr;
    std::string path_;
    std::string phantom_;
    int64_t phantom_size_ = 128;
    double phantom_noise_ = 0.0;
    int phantom_blobs_ = 0;
    uint64_t phantom_seed_ = 1;
    std::string importer_;
    std::string series_;
    std::vector<PluginInstance> importers_;
    PluginOptions options_;
};

} // namespace arbor::cli
