// filter_run.hpp - running a filter plugin on a volume: the host asks for the
// output voxel type, allocates the output on the input's grid, and lets the
// plugin fill it.
#pragma once

#include "plugin_instance.hpp"

#include "../core/volume.hpp"

namespace arbor {

// Throws PluginError naming the filter and its reason.
Volume run_filter(PluginInstance &filter, const Volume &input, ProgressSink *progress,
                  uint64_t max_bytes, std::stop_token stop = {});

} // namespace arbor
