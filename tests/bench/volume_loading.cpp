#include "volume_loading.hpp"

#include "host/plugin_registry.hpp"
#include "host/volume_import.hpp"

#include <cstring>
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

// The slices of `v` repeated to `slices`, mirrored at each end.
Volume stack_mirrored(const Volume &v, int64_t slices)
{
    const Geometry &g = v.geometry();
    const int64_t n = g.dims[2];
    const std::size_t slice_bytes =
        static_cast<std::size_t>(g.dims[0] * g.dims[1]) * arbor_voxel_size(v.type());
    Geometry stacked = g;
    stacked.dims[2] = slices;
    Volume out = Volume::allocate(v.type(), stacked, v.mapping(), kMaxVolumeBytes);
    const auto *from = static_cast<const unsigned char *>(v.data());
    auto *to = static_cast<unsigned char *>(out.data());
    for (int64_t k = 0; k < slices; ++k) {
        const int64_t pass = k / n, at = k % n;
        const int64_t source = pass % 2 == 0 ? at : n - 1 - at;
        std::memcpy(to + static_cast<std::size_t>(k) * slice_bytes, from + static_cast<std::size_t>(source) * slice_bytes,
                    slice_bytes);
    }
    return out;
}

} // namespace

Volume load_input(const BenchInput &input, const std::filesystem::path &file,
                  const std::filesystem::path &plugin_dir)
{
    if (input.phantom)
        return io::make_phantom(io::builtin_phantom("head"), *input.phantom);
    Volume volume = import_file(file, plugin_dir);
    if (input.stacked_slices > 0)
        return stack_mirrored(volume, input.stacked_slices);
    return volume;
}

} // namespace arbor::bench
