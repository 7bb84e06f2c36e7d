// metaimage_importer.cpp - org.arbor.importer.metaimage: ITK MetaImage
// volumes, .mha (data after the header) and .mhd (separate data file), raw,
// zlib-compressed or ASCII.
#include "data_file.hpp"
#include "grid_file_importer.hpp"
#include "header_prefix.hpp"
#include "importer_classes.hpp"
#include "metaimage_header.hpp"
#include "text_scan.hpp"

#include <filesystem>
#include <system_error>

namespace arbor::importers {

const arbor_plugin_descriptor kMetaImageImporterDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.importer.metaimage",
    ARBOR_KIND_IMPORTER,
    "MetaImage",
    "1.0.0",
    "Arbor",
    "Reads ITK MetaImage volumes (.mha with the data inside, .mhd with a separate data "
    "file), raw or zlib-compressed, with their LPS geometry.",
    "",
};

namespace {

// Parses the header and works out where the voxels are; reads no voxel data.
LocatedVolume locate_metaimage(const std::filesystem::path &path)
{
    DataFile file(path);
    const HeaderPrefix prefix = read_header_prefix(file, &metaimage_header_length);
    const MetaImageHeader h = parse_metaimage_header(prefix.text, file.name());
    LocatedVolume v{h.grid, {}, {}};
    VoxelSource &s = v.source;
    uint64_t data_start = 0;
    if (h.data_file.empty()) {
        s.file = path;
        data_start = h.header_length;
    } else {
        s.file = resolve_data_file(path, h.data_file, file.name());
    }
    s.offset = h.header_size > 0 ? static_cast<uint64_t>(h.header_size) : data_start;
    s.encoding =
        h.compressed ? VoxelEncoding::zlib : (h.binary ? VoxelEncoding::raw : VoxelEncoding::ascii);
    s.compressed_size = h.compressed_size;
    s.compression = "zlib";
    s.byte_order = h.byte_order;
    if (h.header_size == -1) {
        if (s.encoding == VoxelEncoding::raw) {
            s.at_end = true;
        } else if (h.compressed && h.compressed_size) {
            const DataFile data(s.file);
            if (data.size() < *h.compressed_size || data.size() - *h.compressed_size < data_start)
                sdk::fail(ARBOR_ERROR_FORMAT, "header of " + file.name() + ": CompressedDataSize " +
                                                  std::to_string(*h.compressed_size) +
                                                  " is larger than the data in " + data.name());
            s.offset = data.size() - *h.compressed_size;
        } else {
            sdk::fail(ARBOR_ERROR_FORMAT,
                      "header of " + file.name() +
                          ": HeaderSize = -1 (data at the end of the file) needs raw "
                          "data, or compressed data with a CompressedDataSize");
        }
    }
    return v;
}

class MetaImageImporter final : public GridFileImporter {
public:
    explicit MetaImageImporter(const arbor_host *host)
        : GridFileImporter(kMetaImageImporterDescriptor, host, ".mha;.mhd")
    {
    }

    int32_t probe(const std::string &path, const uint8_t *head, uint64_t head_size) override
    {
        if (looks_like_metaimage(
                {reinterpret_cast<const char *>(head), static_cast<std::size_t>(head_size)}))
            return 100;
        // A MetaImage suffix without the keys: still ours to explain what is wrong.
        return has_suffix(path, ".mha") || has_suffix(path, ".mhd") ? 10 : 0;
    }

protected:
    LocatedVolume locate(const std::filesystem::path &path) const override
    {
        return locate_metaimage(path);
    }
};

} // namespace

sdk::Instance *create_metaimage_importer(const arbor_host *host)
{
    return new MetaImageImporter(host);
}

} // namespace arbor::importers
