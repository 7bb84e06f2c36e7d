// raw_importer.cpp - org.arbor.importer.raw: headerless raw voxel files.
// Everything a header would say comes from parameters, so read_header checks
// them against the file size (which must match exactly) before the host
// allocates anything.
#include "data_file.hpp"
#include "grid_file_importer.hpp"
#include "importer_classes.hpp"
#include "text_scan.hpp"

#include <filesystem>

namespace arbor::importers {

const arbor_plugin_descriptor kRawImporterDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.importer.raw",
    ARBOR_KIND_IMPORTER,
    "Raw voxels",
    "1.0.0",
    "Arbor",
    "Reads headerless raw voxel files whose dimensions, voxel type, byte order, header offset and "
    "geometry are given as parameters.",
    "",
};

namespace {

constexpr const char *kTypeIds[] = {"u8", "i8", "u16", "i16", "u32", "i32", "f32", "f64"};
constexpr arbor_voxel_type kTypes[] = {ARBOR_VOXEL_U8,  ARBOR_VOXEL_I8,  ARBOR_VOXEL_U16,
                                       ARBOR_VOXEL_I16, ARBOR_VOXEL_U32, ARBOR_VOXEL_I32,
                                       ARBOR_VOXEL_F32, ARBOR_VOXEL_F64};

// Integers travel in doubles (params.h): 2^53 - 1 is the largest exact one.
constexpr double kMaxExactInteger = 9007199254740991.0;

std::vector<sdk::ParamSpec> raw_params()
{
    std::vector<sdk::ParamSpec> p;
    p.push_back(
        sdk::ParamSpec::vector(ARBOR_PARAM_INT, "dims", "Dimensions", {1, 1, 1}, 1, 2147483647)
            .flags(ARBOR_PARAM_FLAG_REQUIRED)
            .unit("voxels")
            .hint("Voxels along x, y and z, x varying fastest in the file, e.g. 256,256,128"));
    p.push_back(sdk::ParamSpec::choice(
                    "type", "Voxel type",
                    std::vector<std::string>(std::begin(kTypeIds), std::end(kTypeIds)), 0,
                    {"unsigned 8-bit", "signed 8-bit", "unsigned 16-bit", "signed 16-bit",
                     "unsigned 32-bit", "signed 32-bit", "32-bit float", "64-bit float"})
                    .hint("How each voxel is stored"));
    p.push_back(sdk::ParamSpec::choice("endian", "Byte order", {"little", "big"}, 0,
                                       {"little endian", "big endian"})
                    .hint("Byte order of voxels wider than one byte"));
    p.push_back(sdk::ParamSpec::integer("header-offset", "Header offset", 0, 0, kMaxExactInteger)
                    .unit("bytes")
                    .hint("Bytes to skip at the start of the file before the first voxel"));
    p.push_back(
        sdk::ParamSpec::vector(ARBOR_PARAM_FLOAT, "spacing", "Spacing", {1, 1, 1}, 1e-9, 1e9)
            .unit("mm")
            .group("Geometry")
            .hint("Distance between voxel centres along x, y and z"));
    p.push_back(sdk::ParamSpec::vector(ARBOR_PARAM_FLOAT, "origin", "Origin", {0, 0, 0}, -1e9, 1e9)
                    .unit("mm")
                    .group("Geometry")
                    .hint("LPS position of the centre of the first voxel"));
    return p;
}

class RawImporter final : public GridFileImporter {
public:
    explicit RawImporter(const arbor_host *host)
        : GridFileImporter(kRawImporterDescriptor, host, ".raw;.bin;.img;.dat", raw_params())
    {
    }

    int32_t probe(const std::string &path, const uint8_t *, uint64_t) override
    {
        // Any file can be read as raw voxels: a low confidence lets importers
        // that recognise the content win.
        for (const char *suffix : {".raw", ".bin", ".img", ".dat"})
            if (has_suffix(path, suffix))
                return 5;
        return 0;
    }

protected:
    LocatedVolume locate(const std::filesystem::path &path) const override
    {
        const std::string name = path.filename().string();
        params().require_all("headerless raw file " + name);
        LocatedVolume v;
        for (int a = 0; a < 3; ++a) {
            v.grid.dims[static_cast<std::size_t>(a)] = params().integer("dims", a);
            v.grid.spacing[static_cast<std::size_t>(a)] = params().number("spacing", a);
            v.grid.origin[static_cast<std::size_t>(a)] = params().number("origin", a);
        }
        const std::string &type = params().choice("type");
        for (std::size_t t = 0; t < std::size(kTypeIds); ++t)
            if (type == kTypeIds[t])
                v.grid.type = kTypes[t];
        v.source.file = path;
        v.source.offset = static_cast<uint64_t>(params().integer("header-offset"));
        v.source.byte_order =
            params().choice("endian") == "big" ? std::endian::big : std::endian::little;
        v.source.exact_size = true;
        v.source.needs = "the parameters (dims " + grid_text(v.grid) + ", header offset " +
                         std::to_string(v.source.offset) + ") need";
        return v;
    }
};

} // namespace

sdk::Instance *create_raw_importer(const arbor_host *host)
{
    return new RawImporter(host);
}

} // namespace arbor::importers
