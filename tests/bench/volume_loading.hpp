// volume_loading.hpp - getting a benchmark input into memory, as the host
// does: files through the importer plugins (probing picks the importer), the
// phantom from its built-in recipe.  Runs in the measuring child process.
#pragma once

#include "bench_inputs.hpp"

#include "core/volume.hpp"

#include <filesystem>

namespace arbor::bench {

// `file` is the input's file (for synthetic fields: its prepared .nhdr);
// ignored for the phantom.  Throws what the host would report.
Volume load_input(const BenchInput &input, const std::filesystem::path &file,
                  const std::filesystem::path &plugin_dir);

} // namespace arbor::bench
