#include "volume_loading.hpp"

#include "host/plugin_registry.hpp"
#include "host/volume_import.hpp"

#include <stdexcept>

namespace arbor::bench {

namespace {

// 512^3 float32 is 512 MiB; allow well beyond the largest input.
constexpr uint64_t kMaxVolumeBytes = uint64_t{8} << 30;

Volume import_file(const std::filesystem::path &file, const std::filesystem::path &plugin_dir)
{
    if (!std::filesystem::exists(file))
        throw std::runtime_error("missing input file " + file.string());
    PluginRegistry registry;
    registry.load_directories({plugin_dir});
    if (registry.plugins().empty())
        throw std::runtime_error("no plugins in " + plugin_dir.string() +
                                 " (build the targets arbor-importers and arbor-importer-vtk)");
    PluginInstance importer = registry.create(choose_importer(registry, file));
    return import_volume(importer, file, nullptr, kMaxVolumeBytes);
}

} // namespace

Volume load_input(const BenchInput &input, const std::filesystem::path &file,
                  const std::filesystem::path &plugin_dir)
{
    if (input.phantom)
        return io::make_phantom(io::builtin_phantom("head"), *input.phantom);
    return import_file(file, plugin_dir);
}

} // namespace arbor::bench
