// The VTK-based importers (org.arbor.importer.vtk-image, org.arbor.importer.nifti)
// on the shared real volumes and on files written here: exact dims, types,
// geometry and statistics, every voxel compared with an independent decode
// (zlib + the file layouts, no VTK), the file's own voxel order for NIfTI
// whatever its qfac, clear errors for malformed files, importer choice by
// probing, progress and cancellation.
#include "independent_decode.hpp"
#include "plugin_fixture.hpp"

#include "core/volume_statistics.hpp"

#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace arbor {
namespace {

namespace fs = std::filesystem;
namespace decode = test::decode;

constexpr const char *kVtkImage = "org.arbor.importer.vtk-image";
constexpr const char *kNifti = "org.arbor.importer.nifti";

// ---- helpers -----------------------------------------------------------------

void expect_dims(const Volume &v, int64_t nx, int64_t ny, int64_t nz)
{
    EXPECT_EQ(v.geometry().dims[0], nx);
    EXPECT_EQ(v.geometry().dims[1], ny);
    EXPECT_EQ(v.geometry().dims[2], nz);
}

void expect_near3(const std::array<double, 3> &got, double x, double y, double z, double tol)
{
    EXPECT_NEAR(got[0], x, tol);
    EXPECT_NEAR(got[1], y, tol);
    EXPECT_NEAR(got[2], z, tol);
}

void expect_direction(const Volume &v, const std::array<double, 9> &expected)
{
    for (int e = 0; e < 9; ++e)
        EXPECT_NEAR(v.geometry().direction[e], expected[e], 1e-6) << "direction element " << e;
}

constexpr std::array<double, 9> kIdentity{1, 0, 0, 0, 1, 0, 0, 0, 1};

// Compares the voxel buffer with the bytes of an independent decode.
void expect_same_bytes(const Volume &v, const std::string &expected)
{
    ASSERT_EQ(v.byte_size(), expected.size());
    const auto *got = static_cast<const char *>(v.data());
    if (std::memcmp(got, expected.data(), expected.size()) == 0)
        return;
    std::size_t first = 0;
    while (got[first] == expected[first])
        ++first;
    ADD_FAILURE() << "voxel bytes differ first at byte " << first;
}

// Imports `path` and expects a failure whose message has every `needle`.
std::string expect_import_failure(const fs::path &path, const std::string &importer,
                                  std::initializer_list<std::string> needles)
{
    try {
        test::import(path, importer);
    } catch (const std::exception &e) {
        const std::string message = e.what();
        for (const std::string &n : needles)
            EXPECT_NE(message.find(n), std::string::npos)
                << "message lacks '" << n << "': " << message;
        return message;
    }
    ADD_FAILURE() << "importing " << path << " did not fail";
    return "";
}

arbor_status import_status(const fs::path &path, const std::string &importer)
{
    try {
        test::import(path, importer);
    } catch (const PluginError &e) {
        return e.status();
    } catch (const std::exception &) {
        return ARBOR_ERROR_INTERNAL;
    }
    return ARBOR_OK;
}

fs::path write_text(const fs::path &path, const std::string &text)
{
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

fs::path write_prefix(const fs::path &from, const fs::path &to, std::size_t bytes)
{
    const std::string all = decode::file_bytes(from);
    return write_text(to, all.substr(0, std::min(bytes, all.size())));
}

// ---- VTK XML and legacy image data -----------------------------------------

TEST(VtkImageImporter, EngineVtiMatchesIndependentDecode)
{
    const fs::path path = test::shared_data("engine/engine.vti");
    const Volume v = test::import(path, kVtkImage);
    EXPECT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 256, 256, 128);
    expect_near3(v.geometry().spacing, 1, 1, 1, 0);
    expect_near3(v.geometry().origin, 0, 0, 0, 0);
    expect_direction(v, kIdentity);
    EXPECT_EQ(v.mapping().scale, 1.0);
    EXPECT_EQ(v.mapping().offset, 0.0);
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_EQ(s.min, 0.0);
    EXPECT_EQ(s.max, 255.0);
    EXPECT_NEAR(s.mean, 22.3, 0.05);
    expect_same_bytes(v, decode::vti_appended_raw_array(path));
}

TEST(VtkImageImporter, BonsaiAndAneurismVtiMatchIndependentDecode)
{
    struct Case {
        const char *file;
        double mean;
    };
    for (const Case c : {Case{"bonsai/bonsai.vti", 13.7}, Case{"aneurism/aneurism.vti", 1.07}}) {
        SCOPED_TRACE(c.file);
        const fs::path path = test::shared_data(c.file);
        const Volume v = test::import(path, kVtkImage);
        EXPECT_EQ(v.type(), ARBOR_VOXEL_U8);
        expect_dims(v, 256, 256, 256);
        expect_near3(v.geometry().spacing, 1, 1, 1, 0);
        expect_near3(v.geometry().origin, 0, 0, 0, 0);
        expect_direction(v, kIdentity);
        const VolumeStatistics s = compute_statistics(v);
        EXPECT_EQ(s.min, 0.0);
        EXPECT_EQ(s.max, 255.0);
        EXPECT_NEAR(s.mean, c.mean, 0.05);
        expect_same_bytes(v, decode::vti_appended_raw_array(path));
    }
}

TEST(VtkImageImporter, HydrogenVtiFloatMatchesIndependentDecode)
{
    const fs::path path = test::shared_data("hydrogen_orbital/hydrogen.vti");
    const Volume v = test::import(path, kVtkImage);
    EXPECT_EQ(v.type(), ARBOR_VOXEL_F32);
    expect_dims(v, 64, 64, 64);
    expect_near3(v.geometry().spacing, 1, 1, 1, 0);
    expect_near3(v.geometry().origin, 0, 0, 0, 0);
    expect_direction(v, kIdentity); // the file's Direction attribute is the identity
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_EQ(s.min, 0.0);
    EXPECT_EQ(s.max, 1.0);
    EXPECT_NEAR(s.mean, 0.019, 0.0005);
    EXPECT_EQ(s.nan_count, 0);
    expect_same_bytes(v, decode::vti_inline_base64_array(path));
}

TEST(VtkImageImporter, IronProtLegacyMatchesFileBytes)
{
    const fs::path path = test::shared_data("ironprot/ironProt.vtk");
    const Volume v = test::import(path, kVtkImage);
    EXPECT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 68, 68, 68);
    expect_near3(v.geometry().spacing, 1, 1, 1, 0);
    expect_near3(v.geometry().origin, 0, 0, 0, 0);
    expect_direction(v, kIdentity);
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_EQ(s.min, 0.0);
    EXPECT_EQ(s.max, 255.0);
    EXPECT_NEAR(s.mean, 13.1, 0.05);
    // Binary legacy data: the 68^3 bytes right after "LOOKUP_TABLE default\n".
    const std::string file = decode::file_bytes(path);
    const std::size_t start = file.find("LOOKUP_TABLE default\n") + 21;
    ASSERT_EQ(start, 209u);
    expect_same_bytes(v, file.substr(start, 68 * 68 * 68));
}

// A .vti whose extent does not start at 0, with a rotation, and no array
// flagged as scalars: the first point-data array is taken, and voxel
// (0, 0, 0) sits at origin + D * (extent start * spacing).
TEST(VtkImageImporter, ExtentStartDirectionAndFirstArray)
{
    const fs::path path = write_text(test::scratch_dir() / "shifted.vti", R"(<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian">
  <ImageData WholeExtent="2 4 1 2 5 6" Origin="10 20 30" Spacing="0.5 2 3" Direction="0 -1 0 1 0 0 0 0 1">
    <Piece Extent="2 4 1 2 5 6">
      <PointData>
        <DataArray type="Int16" Name="density" format="ascii">-1 2 -3 4 -5 6 7 -8 9 10 11 -12</DataArray>
        <DataArray type="Float32" Name="other" format="ascii">0 0 0 0 0 0 0 0 0 0 0 0</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
)");
    const Volume v = test::import(path);
    EXPECT_EQ(v.type(), ARBOR_VOXEL_I16);
    expect_dims(v, 3, 2, 2);
    expect_near3(v.geometry().spacing, 0.5, 2, 3, 1e-12);
    expect_direction(v, {0, -1, 0, 1, 0, 0, 0, 0, 1});
    // origin + D * (2*0.5, 1*2, 5*3) = (10 - 2, 20 + 1, 30 + 15)
    expect_near3(v.geometry().origin, 8, 21, 45, 1e-12);
    const int16_t expected[12] = {-1, 2, -3, 4, -5, 6, 7, -8, 9, 10, 11, -12};
    ASSERT_EQ(v.voxel_count(), 12);
    for (int i = 0; i < 12; ++i)
        EXPECT_EQ(v.as<int16_t>()[i], expected[i]) << "voxel " << i;
}

TEST(VtkImageImporter, NegativeSpacingFlipsTheDirectionInstead)
{
    const fs::path path = write_text(test::scratch_dir() / "flipped.vti", R"(<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian">
  <ImageData WholeExtent="0 1 0 1 0 1" Origin="1 2 3" Spacing="1 -2 1">
    <Piece Extent="0 1 0 1 0 1">
      <PointData Scalars="v">
        <DataArray type="UInt8" Name="v" format="ascii">0 1 2 3 4 5 6 7</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
)");
    const Volume v = test::import(path, kVtkImage);
    expect_near3(v.geometry().spacing, 1, 2, 1, 0);
    expect_direction(v, {1, 0, 0, 0, -1, 0, 0, 0, 1});
    expect_near3(v.geometry().origin, 1, 2, 3, 0);
    // Same positions as VTK: voxel (0, 1, 0) at y = 2 - 2.
    expect_near3(v.geometry().position(0, 1, 0), 1, 0, 3, 1e-12);
}

std::string one_array_vti(const std::string &type, int components = 1)
{
    std::string values;
    for (int i = 0; i < 8 * components; ++i)
        values += std::to_string(i % 100) + " ";
    return R"(<?xml version="1.0"?>
<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian">
  <ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1">
    <Piece Extent="0 1 0 1 0 1">
      <PointData Scalars="a">
        <DataArray type=")" +
           type + R"(" Name="a" NumberOfComponents=")" + std::to_string(components) +
           R"(" format="ascii">)" + values + R"(</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
)";
}

TEST(VtkImageImporter, MapsEveryScalarTypeArborHas)
{
    const fs::path dir = test::scratch_dir();
    const std::pair<const char *, arbor_voxel_type> cases[] = {
        {"Int8", ARBOR_VOXEL_I8},     {"UInt8", ARBOR_VOXEL_U8},   {"Int16", ARBOR_VOXEL_I16},
        {"UInt16", ARBOR_VOXEL_U16},  {"Int32", ARBOR_VOXEL_I32},  {"UInt32", ARBOR_VOXEL_U32},
        {"Float32", ARBOR_VOXEL_F32}, {"Float64", ARBOR_VOXEL_F64},
    };
    for (const auto &[type, expected] : cases) {
        SCOPED_TRACE(type);
        const Volume v = test::import(write_text(dir / (std::string(type) + ".vti"),
                                                 one_array_vti(type)));
        EXPECT_EQ(v.type(), expected);
        ASSERT_EQ(v.voxel_count(), 8);
        for (int i = 0; i < 8; ++i)
            EXPECT_EQ(v.value(i), double(i));
    }
}

TEST(VtkImageImporter, RefusesTypesAndComponentCountsArborLacks)
{
    const fs::path dir = test::scratch_dir();
    const fs::path wide = write_text(dir / "int64.vti", one_array_vti("Int64"));
    expect_import_failure(wide, kVtkImage, {"int64.vti", "long long", "no Arbor voxel type"});
    EXPECT_EQ(import_status(wide, kVtkImage), ARBOR_ERROR_UNSUPPORTED);
    const fs::path rgb = write_text(dir / "rgb.vti", one_array_vti("UInt8", 3));
    expect_import_failure(rgb, kVtkImage, {"rgb.vti", "3 components"});
    EXPECT_EQ(import_status(rgb, kVtkImage), ARBOR_ERROR_UNSUPPORTED);
}

TEST(VtkImageImporter, LegacyAsciiWithSpacingOriginAndFieldData)
{
    const fs::path dir = test::scratch_dir();
    const Volume scalars = test::import(write_text(dir / "ascii.vtk", R"(# vtk DataFile Version 3.0
float scalars
ASCII
DATASET STRUCTURED_POINTS
DIMENSIONS 3 2 2
SPACING 0.5 2 3
ORIGIN 10 20 30
POINT_DATA 12
SCALARS temperature float 1
LOOKUP_TABLE default
0.5 1.5 2.5 3.5 4.5 5.5 6.5 7.5 8.5 9.5 10.5 11.5
)"));
    EXPECT_EQ(scalars.type(), ARBOR_VOXEL_F32);
    expect_dims(scalars, 3, 2, 2);
    expect_near3(scalars.geometry().spacing, 0.5, 2, 3, 0);
    expect_near3(scalars.geometry().origin, 10, 20, 30, 0);
    for (int i = 0; i < 12; ++i)
        EXPECT_EQ(scalars.value(i), i + 0.5);

    // Point data given only as a FIELD array: its type is known only next to
    // the values, and the first array is taken.
    const Volume field = test::import(write_text(dir / "field.vtk", R"(# vtk DataFile Version 3.0
field only
ASCII
DATASET STRUCTURED_POINTS
DIMENSIONS 3 2 2
SPACING 1 1 1
ORIGIN 0 0 0
POINT_DATA 12
FIELD FieldData 1
density 1 12 short
1 2 3 4 5 6 7 8 9 10 11 -12
)"));
    EXPECT_EQ(field.type(), ARBOR_VOXEL_I16);
    expect_dims(field, 3, 2, 2);
    EXPECT_EQ(field.value(0), 1.0);
    EXPECT_EQ(field.value(11), -12.0);
}

// ---- NIfTI --------------------------------------------------------------------

// Voxel data of a .nii.gz, from the decompressed bytes at vox_offset.
std::string nifti_voxel_bytes(const std::string &nii, const decode::Nifti1Header &h)
{
    const std::size_t count = std::size_t(h.dim[1]) * h.dim[2] * h.dim[3] * (h.bitpix / 8);
    return nii.substr(static_cast<std::size_t>(h.vox_offset), count);
}

// LPS direction and spacing expected from an sform (RAS, spacing in its columns).
void expect_sform_geometry(const Volume &v, const decode::Nifti1Header &h)
{
    for (int c = 0; c < 3; ++c) {
        const double x = -h.srow[0][c], y = -h.srow[1][c], z = h.srow[2][c];
        const double length = std::sqrt(x * x + y * y + z * z);
        EXPECT_NEAR(v.geometry().spacing[c], length, 1e-9) << "spacing " << c;
        EXPECT_NEAR(v.geometry().direction[c], x / length, 1e-9);
        EXPECT_NEAR(v.geometry().direction[3 + c], y / length, 1e-9);
        EXPECT_NEAR(v.geometry().direction[6 + c], z / length, 1e-9);
    }
    expect_near3(v.geometry().origin, -h.srow[0][3], -h.srow[1][3], h.srow[2][3], 1e-9);
}

TEST(NiftiImporter, Colin27MatchesIndependentDecodeInFileOrder)
{
    const fs::path path = test::shared_data("mr_brain_colin27/ch2.nii.gz");
    const Volume v = test::import(path, kNifti);
    EXPECT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 181, 217, 181);
    expect_near3(v.geometry().spacing, 1, 1, 1, 1e-9);
    // sform translation (-90, -125, -71) RAS is (90, 125, -71) LPS.
    expect_near3(v.geometry().origin, 90, 125, -71, 1e-9);
    expect_direction(v, {-1, 0, 0, 0, -1, 0, 0, 0, 1});
    EXPECT_EQ(v.mapping().scale, 1.0);
    EXPECT_EQ(v.mapping().offset, 0.0);
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_EQ(s.max, 254.0);
    EXPECT_NEAR(s.mean, 44.6, 0.05);

    const std::string nii = decode::gunzip_file(path);
    const decode::Nifti1Header h = decode::nifti1_header(nii);
    ASSERT_EQ(h.magic, "n+1");
    EXPECT_EQ(h.sform_code, 4);
    expect_sform_geometry(v, h);
    expect_same_bytes(v, nifti_voxel_bytes(nii, h));
}

TEST(NiftiImporter, CtAngioMatchesIndependentDecodeWithSlope)
{
    const fs::path path = test::shared_data("ct_angio_avm/CT_AVM.nii.gz");
    const Volume v = test::import(path, kNifti);
    EXPECT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 256, 242, 154);
    expect_near3(v.geometry().spacing, 0.7199, 0.7209, 1.0, 1e-4);
    EXPECT_NEAR(v.mapping().scale, 2.2086, 1e-4);
    EXPECT_EQ(v.mapping().offset, 0.0);
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_NEAR(s.max * v.mapping().scale, 563.2, 0.1);
    EXPECT_NEAR(s.mean * v.mapping().scale, 5.2, 0.05);

    const std::string nii = decode::gunzip_file(path);
    const decode::Nifti1Header h = decode::nifti1_header(nii);
    EXPECT_EQ(h.sform_code, 1);
    EXPECT_FLOAT_EQ(static_cast<float>(v.mapping().scale), h.scl_slope);
    expect_sform_geometry(v, h);
    expect_same_bytes(v, nifti_voxel_bytes(nii, h));
}

// A NIfTI-1 or NIfTI-2 file written field by field (nifti1.h / nifti2.h
// offsets), little endian, int16 voxels numbered in storage order.
struct NiftiSpec {
    int version = 1;
    bool pair = false; // "ni1": header only, voxels in a separate .img
    int nx = 4, ny = 3, nz = 5, nt = 1;
    int16_t datatype = 4, bitpix = 16; // int16; voxel v holds v
    int vector_components = 1;         // dim[5]
    double pixdim[4] = {1, 1.5, 2, 2.5}; // pixdim[0] is qfac
    int qform_code = 0, sform_code = 0;
    double quatern[3] = {0, 0, 0};
    double qoffset[3] = {0, 0, 0};
    double srow[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
    double scl_slope = 0, scl_inter = 0;
    int xyzt_units = 2;
};

template <class T>
void put(std::string &b, std::size_t offset, T v)
{
    std::memcpy(b.data() + offset, &v, sizeof v);
}

std::string nifti_bytes(const NiftiSpec &s)
{
    const bool two = s.version == 2;
    const std::size_t header = two ? 540 : 348;
    const std::size_t vox_offset = s.pair ? 0 : (two ? 544 : 352);
    std::string b(s.pair ? header : vox_offset, '\0');
    put<int32_t>(b, 0, static_cast<int32_t>(header));
    const int ndim = s.vector_components > 1 ? 5 : (s.nt > 1 ? 4 : 3);
    const int64_t dims[8] = {ndim, s.nx, s.ny, s.nz, s.nt, s.vector_components, 1, 1};
    if (two) {
        std::memcpy(b.data() + 4, "n+2\0\r\n\032\n", 8);
        put<int16_t>(b, 12, s.datatype);
        put<int16_t>(b, 14, s.bitpix);
        for (int i = 0; i < 8; ++i) {
            put<int64_t>(b, 16 + 8 * i, dims[i]);
            put<double>(b, 104 + 8 * i, i < 4 ? s.pixdim[i] : 1.0);
        }
        put<int64_t>(b, 168, static_cast<int64_t>(vox_offset));
        put<double>(b, 176, s.scl_slope);
        put<double>(b, 184, s.scl_inter);
        put<int32_t>(b, 344, s.qform_code);
        put<int32_t>(b, 348, s.sform_code);
        for (int i = 0; i < 3; ++i) {
            put<double>(b, 352 + 8 * i, s.quatern[i]);
            put<double>(b, 376 + 8 * i, s.qoffset[i]);
        }
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                put<double>(b, 400 + 32 * r + 8 * c, s.srow[r][c]);
        put<int32_t>(b, 500, s.xyzt_units);
    } else {
        for (int i = 0; i < 8; ++i) {
            put<int16_t>(b, 40 + 2 * i, static_cast<int16_t>(dims[i]));
            put<float>(b, 76 + 4 * i, static_cast<float>(i < 4 ? s.pixdim[i] : 1.0));
        }
        put<int16_t>(b, 70, s.datatype);
        put<int16_t>(b, 72, s.bitpix);
        put<float>(b, 108, static_cast<float>(vox_offset));
        put<float>(b, 112, static_cast<float>(s.scl_slope));
        put<float>(b, 116, static_cast<float>(s.scl_inter));
        b[123] = static_cast<char>(s.xyzt_units);
        put<int16_t>(b, 252, static_cast<int16_t>(s.qform_code));
        put<int16_t>(b, 254, static_cast<int16_t>(s.sform_code));
        for (int i = 0; i < 3; ++i) {
            put<float>(b, 256 + 4 * i, static_cast<float>(s.quatern[i]));
            put<float>(b, 268 + 4 * i, static_cast<float>(s.qoffset[i]));
        }
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                put<float>(b, 280 + 16 * r + 4 * c, static_cast<float>(s.srow[r][c]));
        std::memcpy(b.data() + 344, s.pair ? "ni1" : "n+1", 4);
    }
    const int values = s.nx * s.ny * s.nz * s.nt * s.vector_components;
    if (s.datatype != 4) {
        b.append(std::size_t(values) * (s.bitpix / 8), '\0');
        return b;
    }
    for (int v = 0; v < values; ++v) {
        const int16_t value = static_cast<int16_t>(v);
        b.append(reinterpret_cast<const char *>(&value), sizeof value);
    }
    return b;
}

fs::path write_nifti(const fs::path &path, const NiftiSpec &spec)
{
    const std::string bytes = nifti_bytes(spec);
    if (spec.pair) {
        const std::size_t header = spec.version == 2 ? 540 : 348;
        write_text(path, bytes.substr(0, header));
        write_text(fs::path(path).replace_extension(".img"), bytes.substr(header));
    } else if (path.extension() == ".gz") {
        gzFile f = gzopen(path.c_str(), "wb");
        gzwrite(f, bytes.data(), static_cast<unsigned>(bytes.size()));
        gzclose(f);
    } else {
        write_text(path, bytes);
    }
    return path;
}

// Voxel v holds the value v: storage order survived.
void expect_file_order(const Volume &v)
{
    ASSERT_EQ(v.type(), ARBOR_VOXEL_I16);
    for (int64_t i = 0; i < v.voxel_count(); ++i)
        ASSERT_EQ(v.as<int16_t>()[i], i) << "voxel " << i << " is not in file order";
}

TEST(NiftiImporter, QformWithNegativeQfacKeepsFileOrder)
{
    NiftiSpec s;
    s.pixdim[0] = -1; // qfac: vtkNIFTIImageReader reverses the slices for this
    s.qform_code = 1;
    s.qoffset[0] = 5;
    s.qoffset[1] = 6;
    s.qoffset[2] = 7;
    const Volume v = test::import(write_nifti(test::scratch_dir() / "qfac.nii", s));
    expect_dims(v, 4, 3, 5);
    expect_file_order(v);
    expect_near3(v.geometry().spacing, 1.5, 2, 2.5, 1e-6);
    // Identity rotation, k flipped by qfac; RAS -> LPS negates x and y.
    expect_direction(v, {-1, 0, 0, 0, -1, 0, 0, 0, -1});
    expect_near3(v.geometry().origin, -5, -6, 7, 1e-6);
}

TEST(NiftiImporter, LeftHandedSformWithoutQformKeepsFileOrder)
{
    NiftiSpec s;
    s.sform_code = 2;
    // i along -x (RAS), j along +y, k along +z: a left-handed grid.
    const double srow[3][4] = {{-1.5, 0, 0, 10}, {0, 2, 0, 20}, {0, 0, 2.5, 30}};
    std::memcpy(s.srow, srow, sizeof srow);
    const Volume v = test::import(write_nifti(test::scratch_dir() / "sform.nii.gz", s));
    expect_file_order(v);
    expect_near3(v.geometry().spacing, 1.5, 2, 2.5, 1e-6);
    expect_direction(v, {1, 0, 0, 0, -1, 0, 0, 0, 1});
    expect_near3(v.geometry().origin, -10, -20, 30, 1e-6);
}

TEST(NiftiImporter, QuaternionRotationAndUnits)
{
    NiftiSpec s;
    s.qform_code = 1;
    // 90 degrees about z: b = c = 0, d = sin(45 deg).
    s.quatern[2] = std::sqrt(0.5);
    s.xyzt_units = 3; // microns
    s.pixdim[1] = 1000;
    s.pixdim[2] = 2000;
    s.pixdim[3] = 3000;
    const Volume v = test::import(write_nifti(test::scratch_dir() / "rotated.nii", s));
    expect_file_order(v);
    expect_near3(v.geometry().spacing, 1, 2, 3, 1e-6);
    // RAS columns (0,1,0), (-1,0,0), (0,0,1) -> LPS (0,-1,0), (1,0,0), (0,0,1).
    expect_direction(v, {0, 1, 0, -1, 0, 0, 0, 0, 1});
}

TEST(NiftiImporter, Nifti2WithSlopeAndMetres)
{
    NiftiSpec s;
    s.version = 2;
    s.sform_code = 1;
    const double srow[3][4] = {{0.001, 0, 0, 0.1}, {0, 0.001, 0, 0.2}, {0, 0, 0.002, 0.3}};
    std::memcpy(s.srow, srow, sizeof srow);
    s.xyzt_units = 1; // metres
    s.scl_slope = 0.5;
    s.scl_inter = -3;
    const fs::path path = write_nifti(test::scratch_dir() / "two.nii", s);
    EXPECT_EQ(choose_importer(test::built_plugins(), path), kNifti);
    const Volume v = test::import(path);
    expect_file_order(v);
    expect_near3(v.geometry().spacing, 1, 1, 2, 1e-9);
    expect_near3(v.geometry().origin, -100, -200, 300, 1e-9);
    EXPECT_EQ(v.mapping().scale, 0.5);
    EXPECT_EQ(v.mapping().offset, -3.0);
}

TEST(NiftiImporter, ZeroSlopeMeansNoScalingAndPixdimAlonePlaces)
{
    NiftiSpec s; // no qform, no sform, slope 0
    s.scl_inter = 7;
    const Volume v = test::import(write_nifti(test::scratch_dir() / "plain.nii", s));
    EXPECT_EQ(v.mapping().scale, 1.0);
    EXPECT_EQ(v.mapping().offset, 0.0);
    expect_near3(v.geometry().spacing, 1.5, 2, 2.5, 1e-6);
    expect_near3(v.geometry().origin, 0, 0, 0, 0);
    expect_direction(v, {-1, 0, 0, 0, -1, 0, 0, 0, 1});
}

TEST(NiftiImporter, SeriesGiveTheirFirstVolume)
{
    NiftiSpec s;
    s.nt = 3;
    const Volume v = test::import(write_nifti(test::scratch_dir() / "series.nii", s));
    expect_dims(v, 4, 3, 5);
    expect_file_order(v); // values 0..59: the first of the three volumes
}

TEST(NiftiImporter, HeaderAndImagePair)
{
    NiftiSpec s;
    s.pair = true;
    s.qform_code = 1;
    s.pixdim[0] = -1;
    const fs::path header = write_nifti(test::scratch_dir() / "pair.hdr", s);
    EXPECT_EQ(choose_importer(test::built_plugins(), header), kNifti);
    const Volume v = test::import(header);
    expect_dims(v, 4, 3, 5);
    expect_file_order(v);
}

TEST(NiftiImporter, RefusesMultiComponentAnd64BitData)
{
    const fs::path dir = test::scratch_dir();
    NiftiSpec rgb;
    rgb.datatype = 128; // RGB24
    rgb.bitpix = 24;
    const fs::path rgb_path = write_nifti(dir / "rgb.nii", rgb);
    expect_import_failure(rgb_path, kNifti, {"rgb.nii", "RGB24", "3 components"});
    EXPECT_EQ(import_status(rgb_path, kNifti), ARBOR_ERROR_UNSUPPORTED);

    NiftiSpec vectors;
    vectors.vector_components = 3;
    expect_import_failure(write_nifti(dir / "vectors.nii", vectors), kNifti,
                          {"vectors.nii", "dim[5] = 3"});

    NiftiSpec wide;
    wide.datatype = 1024; // int64
    wide.bitpix = 64;
    const fs::path wide_path = write_nifti(dir / "int64.nii", wide);
    expect_import_failure(wide_path, kNifti, {"int64.nii", "int64", "no Arbor voxel type"});
    EXPECT_EQ(import_status(wide_path, kNifti), ARBOR_ERROR_UNSUPPORTED);
}

// ---- malformed input ------------------------------------------------------------

TEST(VtkImporterRobustness, TruncatedFilesFailWithReasons)
{
    const fs::path dir = test::scratch_dir();
    const fs::path engine = test::shared_data("engine/engine.vti");
    const fs::path hydrogen = test::shared_data("hydrogen_orbital/hydrogen.vti");
    const fs::path iron = test::shared_data("ironprot/ironProt.vtk");
    const fs::path colin = test::shared_data("mr_brain_colin27/ch2.nii.gz");

    expect_import_failure(write_prefix(engine, dir / "cut-in-xml.vti", 300), kVtkImage,
                          {"cut-in-xml.vti", "XML"});
    expect_import_failure(write_prefix(engine, dir / "cut-in-data.vti", 100000), kVtkImage,
                          {"cut-in-data.vti", "ImageFile"});
    expect_import_failure(write_prefix(hydrogen, dir / "cut-inline.vti", 5000), kVtkImage,
                          {"cut-inline.vti"});
    expect_import_failure(write_prefix(iron, dir / "cut-in-data.vtk", 100000), kVtkImage,
                          {"cut-in-data.vtk", "truncated"});
    expect_import_failure(write_prefix(iron, dir / "cut-in-header.vtk", 150), kVtkImage,
                          {"cut-in-header.vtk"});
    expect_import_failure(write_prefix(colin, dir / "cut.nii.gz", 100000), kNifti,
                          {"cut.nii.gz", "truncated"});
    expect_import_failure(write_prefix(colin, dir / "cut-header.nii.gz", 200), kNifti,
                          {"cut-header.nii.gz", "header"});

    // Legacy data shorter than declared, in files large enough to pass the
    // size check: VTK's legacy reader only warns, which is still a failure.
    expect_import_failure(write_text(dir / "few-values.vtk", R"(# vtk DataFile Version 3.0
six of twelve values
ASCII
DATASET STRUCTURED_POINTS
DIMENSIONS 3 2 2
SPACING 1 1 1
ORIGIN 0 0 0
POINT_DATA 12
SCALARS s float 1
LOOKUP_TABLE default
1.000000000000 2.000000000000 3.000000000000 4.000000000000 5.000000000000 6.000000000000
)"),
                          kVtkImage, {"few-values.vtk", "ascii data"});
    expect_import_failure(write_text(dir / "few-bytes.vtk",
                                     "# vtk DataFile Version 3.0\n" + std::string(200, 'T') +
                                         "\nBINARY\nDATASET STRUCTURED_POINTS\n"
                                         "DIMENSIONS 4 4 4\nSPACING 1 1 1\nORIGIN 0 0 0\n"
                                         "POINT_DATA 64\nSCALARS s unsigned_char 1\n"
                                         "LOOKUP_TABLE default\n" +
                                         std::string(10, '\1')),
                          kVtkImage, {"few-bytes.vtk", "binary data"});

    // An uncompressed .nii cut short is refused from its header alone.
    const std::string nii = decode::gunzip_file(colin);
    const fs::path short_nii = write_text(dir / "short.nii", nii.substr(0, 50000));
    expect_import_failure(short_nii, kNifti, {"short.nii", "truncated", "vox_offset 352"});

    for (const char *name : {"cut-in-data.vti", "cut-in-data.vtk", "cut.nii.gz", "short.nii"})
        EXPECT_EQ(import_status(dir / name, std::string(name).find(".vt") != std::string::npos
                                                ? kVtkImage
                                                : kNifti),
                  ARBOR_ERROR_FORMAT)
            << name;
}

// VTK 9.1's NIfTI reader trusts these fields (an unknown datatype code
// crashes it); the importer's own header check refuses them first.
TEST(VtkImporterRobustness, DamagedNiftiHeaderFieldsNeverReachVtk)
{
    const fs::path dir = test::scratch_dir();
    struct Damage {
        const char *file;
        std::size_t offset;
        int16_t value;
        const char *needle;
    };
    for (const Damage d : {Damage{"datatype.nii", 70, 16256, "unknown NIfTI datatype code 16256"},
                           Damage{"bitpix.nii", 72, 7, "bitpix 7"},
                           Damage{"ndim.nii", 40, 9, "dim[0] is 9"},
                           Damage{"negative.nii", 44, -3, "dim[2] is -3"}}) {
        std::string bytes = nifti_bytes(NiftiSpec{});
        put<int16_t>(bytes, d.offset, d.value);
        const fs::path path = write_text(dir / d.file, bytes);
        expect_import_failure(path, kNifti, {d.file, d.needle});
        EXPECT_EQ(import_status(path, kNifti), ARBOR_ERROR_FORMAT) << d.file;
    }
    std::string inside = nifti_bytes(NiftiSpec{});
    put<float>(inside, 108, 100.0f);
    expect_import_failure(write_text(dir / "offset.nii", inside), kNifti,
                          {"offset.nii", "vox_offset 100"});
    std::string analyze = nifti_bytes(NiftiSpec{});
    std::memset(analyze.data() + 344, 0, 4);
    const fs::path analyze_path = write_text(dir / "analyze.nii", analyze);
    expect_import_failure(analyze_path, kNifti, {"analyze.nii", "Analyze 7.5"});
    EXPECT_EQ(import_status(analyze_path, kNifti), ARBOR_ERROR_UNSUPPORTED);
}

TEST(VtkImporterRobustness, GarbageEmptyAndMissingFiles)
{
    const fs::path dir = test::scratch_dir();
    std::string garbage(5000, '\0');
    uint32_t x = 12345;
    for (char &c : garbage) {
        x = x * 1664525u + 1013904223u;
        c = static_cast<char>(x >> 24);
    }
    for (const char *name : {"garbage.vti", "garbage.vtk"})
        expect_import_failure(write_text(dir / name, garbage), kVtkImage,
                              {name, "not a VTK image file"});
    for (const char *name : {"garbage.nii.gz", "garbage.nii"})
        expect_import_failure(write_text(dir / name, garbage), kNifti, {name, "NIfTI header"});
    for (const char *name : {"empty.vti", "empty.vtk"}) {
        expect_import_failure(write_text(dir / name, ""), kVtkImage, {name, "empty"});
        EXPECT_EQ(import_status(dir / name, kVtkImage), ARBOR_ERROR_FORMAT);
    }
    expect_import_failure(write_text(dir / "empty.nii.gz", ""), kNifti, {"empty.nii.gz", "empty"});

    EXPECT_EQ(import_status(dir / "missing.vti", kVtkImage), ARBOR_ERROR_IO);
    EXPECT_EQ(import_status(dir / "missing.nii.gz", kNifti), ARBOR_ERROR_IO);
    expect_import_failure(dir / "missing.vti", kVtkImage, {"missing.vti", "no such file"});
}

TEST(VtkImporterRobustness, OtherDatasetTypesAreNamed)
{
    const fs::path dir = test::scratch_dir();
    const fs::path poly = write_text(dir / "triangle.vtk", R"(# vtk DataFile Version 3.0
one triangle
ASCII
DATASET POLYDATA
POINTS 3 float
0 0 0 1 0 0 0 1 0
POLYGONS 1 4
3 0 1 2
)");
    // Chosen by probing: the importer explains rather than "nobody reads it".
    expect_import_failure(poly, "", {"triangle.vtk", "POLYDATA", "STRUCTURED_POINTS"});
    EXPECT_EQ(import_status(poly, kVtkImage), ARBOR_ERROR_UNSUPPORTED);

    const fs::path vtp = write_text(dir / "mesh.vti", R"(<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian">
  <PolyData><Piece NumberOfPoints="0" NumberOfPolys="0"></Piece></PolyData>
</VTKFile>
)");
    expect_import_failure(vtp, kVtkImage, {"mesh.vti", "PolyData", "ImageData"});
    EXPECT_EQ(import_status(vtp, kVtkImage), ARBOR_ERROR_UNSUPPORTED);

    const fs::path wrong_dims = write_text(dir / "too-many.vtk", R"(# vtk DataFile Version 3.0
claims far more voxels than it holds
BINARY
DATASET STRUCTURED_POINTS
DIMENSIONS 1000 1000 1000
SPACING 1 1 1
ORIGIN 0 0 0
POINT_DATA 1000000000
SCALARS s unsigned_char
LOOKUP_TABLE default
abc
)");
    expect_import_failure(wrong_dims, kVtkImage, {"too-many.vtk", "1000 x 1000 x 1000"});
}

TEST(VtkImporterRobustness, NothingReachesTheTerminalButTheHostLogGetsVtkText)
{
    const fs::path dir = test::scratch_dir();
    const fs::path bad = write_prefix(test::shared_data("engine/engine.vti"), dir / "cut.vti", 300);
    testing::internal::CaptureStderr();
    EXPECT_NE(import_status(bad, kVtkImage), ARBOR_OK);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");

    const arbor_log_level saved = log_level();
    set_log_level(ARBOR_LOG_DEBUG);
    testing::internal::CaptureStderr();
    EXPECT_NE(import_status(bad, kVtkImage), ARBOR_OK);
    const std::string log = testing::internal::GetCapturedStderr();
    set_log_level(saved);
    EXPECT_NE(log.find("[" + std::string(kVtkImage) + "] VTK error:"), std::string::npos) << log;
    EXPECT_EQ(log.find("ERR|"), std::string::npos) << log; // vtkLogger stayed quiet
}

// ---- choice by probing --------------------------------------------------------

TEST(VtkImporterProbing, ProbingPicksTheseImporters)
{
    const std::pair<const char *, const char *> cases[] = {
        {"engine/engine.vti", kVtkImage},
        {"bonsai/bonsai.vti", kVtkImage},
        {"aneurism/aneurism.vti", kVtkImage},
        {"hydrogen_orbital/hydrogen.vti", kVtkImage},
        {"ironprot/ironProt.vtk", kVtkImage},
        {"mr_brain_colin27/ch2.nii.gz", kNifti},
        {"ct_angio_avm/CT_AVM.nii.gz", kNifti},
    };
    for (const auto &[file, id] : cases) {
        const auto ranked = rank_importers(test::built_plugins(), test::shared_data(file));
        ASSERT_FALSE(ranked.empty()) << file;
        EXPECT_EQ(ranked.front().id, id) << file;
        EXPECT_EQ(ranked.front().confidence, 100) << file;
    }
}

TEST(VtkImporterProbing, ContentBeatsSuffix)
{
    const fs::path dir = test::scratch_dir();
    // A NIfTI file with a misleading name is still recognised by its magic.
    const fs::path renamed = dir / "volume.dat";
    fs::copy_file(test::shared_data("ct_angio_avm/CT_AVM.nii.gz"), renamed);
    EXPECT_EQ(choose_importer(test::built_plugins(), renamed), kNifti);
    // A .vti that holds a legacy STRUCTURED_POINTS file reads as one.
    const fs::path legacy = dir / "legacy.vti";
    fs::copy_file(test::shared_data("ironprot/ironProt.vtk"), legacy);
    const Volume v = test::import(legacy);
    expect_dims(v, 68, 68, 68);
    // Suffix alone gives a low but non-zero confidence.
    const fs::path garbage = write_text(dir / "unknown.nii.gz", "not a NIfTI file at all");
    const auto ranked = rank_importers(test::built_plugins(), garbage);
    ASSERT_FALSE(ranked.empty());
    EXPECT_EQ(ranked.front().id, kNifti);
    EXPECT_LT(ranked.front().confidence, 100);
}

// ---- progress and cancellation --------------------------------------------------

class RecordingSink : public ProgressSink {
public:
    void report(const std::string &, double fraction) override { fractions.push_back(fraction); }
    void finish() override {}
    std::vector<double> fractions;
};

struct HeaderAndInstance {
    PluginInstance instance;
    const arbor_importer_v1 *table;
    arbor_volume header;
};

HeaderAndInstance open_header(const std::string &id, const fs::path &path)
{
    HeaderAndInstance h{test::built_plugins().create(id), nullptr, {}};
    h.table = &h.instance.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
    h.header.struct_size = sizeof(arbor_volume);
    Task task;
    h.instance.check(h.table->read_header(h.instance.get(), path.c_str(), task.get(), &h.header),
                     "reading the header");
    return h;
}

TEST(VtkImporterTasks, ReportsProgressUpToTheEnd)
{
    for (const auto &[id, file] : {std::pair{kVtkImage, "bonsai/bonsai.vti"},
                                   std::pair{kNifti, "mr_brain_colin27/ch2.nii.gz"}}) {
        SCOPED_TRACE(file);
        const fs::path path = test::shared_data(file);
        HeaderAndInstance h = open_header(id, path);
        Volume volume = Volume::allocate(h.header, uint64_t{1} << 32);
        arbor_volume target = volume.view();
        RecordingSink sink;
        {
            Task task(&sink);
            ASSERT_EQ(h.table->read_voxels(h.instance.get(), path.c_str(), task.get(), &target),
                      ARBOR_OK)
                << h.instance.last_error();
        }
        ASSERT_GT(sink.fractions.size(), 10u);
        EXPECT_DOUBLE_EQ(sink.fractions.back(), 1.0);
        for (std::size_t i = 1; i < sink.fractions.size(); ++i)
            EXPECT_GE(sink.fractions[i], sink.fractions[i - 1]);
    }
}

TEST(VtkImporterTasks, CancellationStopsTheRead)
{
    for (const auto &[id, file] : {std::pair{kVtkImage, "bonsai/bonsai.vti"},
                                   std::pair{kVtkImage, "ironprot/ironProt.vtk"},
                                   std::pair{kNifti, "mr_brain_colin27/ch2.nii.gz"}}) {
        SCOPED_TRACE(file);
        const fs::path path = test::shared_data(file);
        HeaderAndInstance h = open_header(id, path);
        Volume volume = Volume::allocate(h.header, uint64_t{1} << 32);
        arbor_volume target = volume.view();
        Task task;
        task.cancel();
        EXPECT_EQ(h.table->read_voxels(h.instance.get(), path.c_str(), task.get(), &target),
                  ARBOR_ERROR_CANCELLED);
        EXPECT_NE(h.instance.last_error().find("cancelled"), std::string::npos);
    }
}

} // namespace
} // namespace arbor
