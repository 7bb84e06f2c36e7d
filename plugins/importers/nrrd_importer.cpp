// nrrd_importer.cpp - org.arbor.importer.nrrd: NRRD volumes with attached
// (.nrrd) or detached (.nhdr) headers, raw, gzip or ascii encoded.
#include "data_file.hpp"
#include "grid_file_importer.hpp"
#include "header_prefix.hpp"
#include "importer_classes.hpp"
#include "nrrd_header.hpp"
#include "text_scan.hpp"

#include <filesystem>

namespace arbor::importers {

const arbor_plugin_descriptor kNrrdImporterDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.importer.nrrd",
    ARBOR_KIND_IMPORTER,
    "NRRD",
    "1.0.0",
    "Arbor",
    "Reads NRRD volumes with attached (.nrrd) or detached (.nhdr) headers, raw, gzip or ASCII "
    "encoded, with their geometry converted to LPS.",
    "",
};

namespace {

// Parses the header and works out where the voxels are; reads no voxel data.
LocatedVolume locate_nrrd(const std::filesystem::path &path)
{
    DataFile file(path);
    const HeaderPrefix prefix = read_header_prefix(file, &nrrd_header_length);
    NrrdHeader h = parse_nrrd_header(prefix.text, file.name());
    LocatedVolume v{h.grid, {}, std::move(h.mapping)};
    VoxelSource &s = v.source;
    if (h.data_file.empty()) {
        if (!prefix.ended)
            sdk::fail(ARBOR_ERROR_FORMAT, "header of " + file.name() +
                                              ": no 'data file' field and no blank line ending the "
                                              "header, so the file holds no voxel data");
        s.file = path;
        s.offset = prefix.text.size();
    } else {
        s.file = resolve_data_file(path, h.data_file, file.name());
    }
    s.line_skip = static_cast<uint64_t>(h.line_skip);
    s.at_end = h.byte_skip == -1;
    s.byte_skip = h.byte_skip > 0 ? static_cast<uint64_t>(h.byte_skip) : 0;
    switch (h.encoding) {
    case NrrdEncoding::raw: s.encoding = VoxelEncoding::raw; break;
    case NrrdEncoding::gzip: s.encoding = VoxelEncoding::zlib; break;
    case NrrdEncoding::ascii: s.encoding = VoxelEncoding::ascii; break;
    }
    s.compression = "gzip";
    s.byte_order = h.byte_order;
    return v;
}

class NrrdImporter final : public GridFileImporter {
public:
    explicit NrrdImporter(const arbor_host *host)
        : GridFileImporter(kNrrdImporterDescriptor, host, ".nrrd;.nhdr")
    {
    }

    int32_t probe(const std::string &path, const uint8_t *head, uint64_t head_size) override
    {
        if (has_nrrd_magic(
                {reinterpret_cast<const char *>(head), static_cast<std::size_t>(head_size)}))
            return 100;
        // A NRRD suffix without the magic: still ours to explain what is wrong.
        return has_suffix(path, ".nrrd") || has_suffix(path, ".nhdr") ? 10 : 0;
    }

protected:
    LocatedVolume locate(const std::filesystem::path &path) const override
    {
        return locate_nrrd(path);
    }
};

} // namespace

sdk::Instance *create_nrrd_importer(const arbor_host *host)
{
    return new NrrdImporter(host);
}

} // namespace arbor::importers
