// The NRRD, MetaImage and headerless raw importers (plugins/importers) read
// the shared real volumes exactly: every voxel is compared with an independent
// reading done here (std::ifstream, our own byte swapping, zlib), and the
// geometry and statistics with the data sets' READMEs.  Malformed files,
// generated in the scratch folder, must fail with a message that names the
// problem, never crash.
#include "plugin_fixture.hpp"

#include "io/nrrd_writer.hpp"
#include "host/host_services.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace arbor {
namespace {

namespace fs = std::filesystem;

// decode() and the hand-written big-endian test data assume it.
static_assert(std::endian::native == std::endian::little, "these tests assume a little-endian host");

constexpr const char *kNrrd = "org.arbor.importer.nrrd";
constexpr const char *kMetaImage = "org.arbor.importer.metaimage";
constexpr const char *kRaw = "org.arbor.importer.raw";

// ---- independent reading ------------------------------------------------------

// Appends [first, last) to `bytes`.  (Resizing first, then copying, keeps
// GCC 12 from a false -Warray-bounds report on vector::insert.)
template <class It>
void append(std::vector<uint8_t> &bytes, It first, It last)
{
    const std::size_t old = bytes.size();
    bytes.resize(old + static_cast<std::size_t>(std::distance(first, last)));
    std::copy(first, last, bytes.begin() + static_cast<std::ptrdiff_t>(old));
}

std::vector<uint8_t> read_bytes(const fs::path &path)
{
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in.good()) << path;
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in),
                                std::istreambuf_iterator<char>());
}

std::size_t offset_after(const std::vector<uint8_t> &bytes, const std::string &marker)
{
    const auto it = std::search(bytes.begin(), bytes.end(), marker.begin(), marker.end());
    EXPECT_NE(it, bytes.end()) << "marker not found: " << marker;
    return static_cast<std::size_t>(it - bytes.begin()) + marker.size();
}

// Inflates a zlib or gzip stream (zlib detects which) to its end.
std::vector<uint8_t> inflate_all(const uint8_t *data, std::size_t size)
{
    z_stream z{};
    EXPECT_EQ(inflateInit2(&z, 15 + 32), Z_OK);
    std::vector<uint8_t> out;
    std::vector<uint8_t> chunk(1 << 20);
    z.next_in = const_cast<uint8_t *>(data);
    z.avail_in = static_cast<uInt>(size);
    int status = Z_OK;
    while (status == Z_OK) {
        z.next_out = chunk.data();
        z.avail_out = static_cast<uInt>(chunk.size());
        status = inflate(&z, Z_NO_FLUSH);
        append(out, chunk.begin(),
               chunk.begin() + static_cast<std::ptrdiff_t>(chunk.size() - z.avail_out));
    }
    EXPECT_EQ(status, Z_STREAM_END);
    inflateEnd(&z);
    return out;
}

std::vector<uint8_t> gzip_bytes(const std::vector<uint8_t> &data)
{
    z_stream z{};
    EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::vector<uint8_t> out(deflateBound(&z, data.size()) + 64);
    z.next_in = const_cast<uint8_t *>(data.data());
    z.avail_in = static_cast<uInt>(data.size());
    z.next_out = out.data();
    z.avail_out = static_cast<uInt>(out.size());
    EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

std::vector<uint8_t> zlib_bytes(const std::vector<uint8_t> &data)
{
    uLongf size = compressBound(data.size());
    std::vector<uint8_t> out(size);
    EXPECT_EQ(compress(out.data(), &size, data.data(), data.size()), Z_OK);
    out.resize(size);
    return out;
}

// Values of type T stored in `bytes` from `offset` on, in the given order.
template <class T>
std::vector<T> decode(const std::vector<uint8_t> &bytes, std::size_t offset, bool big_endian,
                      std::size_t count)
{
    EXPECT_GE(bytes.size(), offset + count * sizeof(T));
    std::vector<T> values(count);
    for (std::size_t i = 0; i < count && offset + (i + 1) * sizeof(T) <= bytes.size(); ++i) {
        uint8_t b[sizeof(T)];
        for (std::size_t k = 0; k < sizeof(T); ++k)
            b[k] = bytes[offset + i * sizeof(T) + (big_endian ? sizeof(T) - 1 - k : k)];
        std::memcpy(&values[i], b, sizeof(T));
    }
    return values;
}

// Every voxel of `volume` equals `expected`.
template <class T>
void expect_voxels(const Volume &volume, const std::vector<T> &expected)
{
    ASSERT_EQ(static_cast<std::size_t>(volume.voxel_count()), expected.size());
    const T *v = volume.as<T>();
    std::size_t differing = 0, first = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
        if (v[i] != expected[i] && differing++ == 0)
            first = i;
    EXPECT_EQ(differing, 0u) << "first difference at voxel " << first << ": " << +v[first]
                             << " instead of " << +expected[first];
}

struct Stats {
    double min = 0, max = 0, mean = 0;
};

template <class T>
Stats stats(const Volume &volume)
{
    const T *v = volume.as<T>();
    Stats s{static_cast<double>(v[0]), static_cast<double>(v[0]), 0.0};
    double sum = 0;
    for (int64_t i = 0; i < volume.voxel_count(); ++i) {
        s.min = std::min(s.min, static_cast<double>(v[i]));
        s.max = std::max(s.max, static_cast<double>(v[i]));
        sum += static_cast<double>(v[i]);
    }
    s.mean = sum / static_cast<double>(volume.voxel_count());
    return s;
}

void expect_dims(const Volume &v, int64_t x, int64_t y, int64_t z)
{
    EXPECT_EQ(v.geometry().dims[0], x);
    EXPECT_EQ(v.geometry().dims[1], y);
    EXPECT_EQ(v.geometry().dims[2], z);
}

void expect_direction(const Volume &v, const std::array<double, 9> &d, double tolerance = 1e-12)
{
    for (int e = 0; e < 9; ++e)
        EXPECT_NEAR(v.geometry().direction[e], d[e], tolerance) << "direction element " << e;
}

constexpr std::array<double, 9> kIdentity{1, 0, 0, 0, 1, 0, 0, 0, 1};

void expect_unit_geometry(const Volume &v)
{
    for (int a = 0; a < 3; ++a) {
        EXPECT_DOUBLE_EQ(v.geometry().spacing[a], 1.0);
        EXPECT_DOUBLE_EQ(v.geometry().origin[a], 0.0);
    }
    expect_direction(v, kIdentity, 0.0);
    EXPECT_DOUBLE_EQ(v.mapping().scale, 1.0);
    EXPECT_DOUBLE_EQ(v.mapping().offset, 0.0);
}

// ---- generated files ----------------------------------------------------------

fs::path write_file(const fs::path &path, const std::string &text,
                    const std::vector<uint8_t> &bytes = {})
{
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.write(reinterpret_cast<const char *>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    return path;
}

std::vector<uint8_t> counting_bytes(std::size_t n)
{
    std::vector<uint8_t> b(n);
    for (std::size_t i = 0; i < n; ++i)
        b[i] = static_cast<uint8_t>((i * 7 + i / 251) & 0xff);
    return b;
}

// The message of what `body` throws; fails the test when it throws nothing.
template <class Body>
std::string failure_of(Body &&body)
{
    try {
        body();
    } catch (const std::exception &e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an error";
    return "";
}

// The status of the PluginError `body` throws (ARBOR_OK when it throws none
// or another exception).
template <class Body>
arbor_status status_of(Body &&body)
{
    try {
        body();
    } catch (const PluginError &e) {
        return e.status();
    } catch (const std::exception &) {
    }
    return ARBOR_OK;
}

#define EXPECT_MENTIONS(text, words)                                                               \
    EXPECT_NE(std::string(text).find(words), std::string::npos) << "message: " << (text)

const std::string kU8Header = "NRRD0004\ntype: uint8\ndimension: 3\n";

// ---- the shared real volumes ------------------------------------------------

TEST(ImportersBasic, NucleonOldDatafileForm)
{
    const fs::path header = test::shared_data("nucleon/nucleon.nrrd");
    const Volume v = test::import(header);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 41, 41, 41);
    expect_unit_geometry(v);
    expect_voxels(v, read_bytes(test::shared_data("nucleon/nucleon.raw")));
    const Stats s = stats<uint8_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 249);
    EXPECT_NEAR(s.mean, 39.4, 0.05);
}

TEST(ImportersBasic, DetachedEightBitHeaders)
{
    struct Case {
        const char *header, *raw;
        int64_t x, y, z;
        double max, mean;
    };
    const Case cases[] = {
        // The bucky README rounds its mean, 35.8498, up to 35.9.
        {"bucky/bucky.nhdr", "bucky/Bucky.raw", 32, 32, 32, 255, 35.85},
        {"neghip/neghip.nhdr", "neghip/neghip_64x64x64_uint8.raw", 64, 64, 64, 255, 18.4},
        {"tooth/tooth.nhdr", "tooth/tooth_103x94x161_uint8.raw", 103, 94, 161, 255, 103.2},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.header);
        const Volume v = test::import(test::shared_data(c.header));
        ASSERT_EQ(v.type(), ARBOR_VOXEL_U8);
        expect_dims(v, c.x, c.y, c.z);
        expect_unit_geometry(v);
        expect_voxels(v, read_bytes(test::shared_data(c.raw)));
        const Stats s = stats<uint8_t>(v);
        EXPECT_EQ(s.min, 0);
        EXPECT_EQ(s.max, c.max);
        EXPECT_NEAR(s.mean, c.mean, 0.05);
    }
}

TEST(ImportersBasic, Tooth16BigEndian)
{
    const Volume v = test::import(test::shared_data("tooth16_bigendian/tooth.nhdr"));
    ASSERT_EQ(v.type(), ARBOR_VOXEL_U16);
    expect_dims(v, 103, 94, 161);
    expect_unit_geometry(v);
    const auto raw = read_bytes(test::shared_data("tooth16_bigendian/tooth.raw"));
    expect_voxels(v, decode<uint16_t>(raw, 0, true, 103 * 94 * 161));
    const Stats s = stats<uint16_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 1300);
    EXPECT_NEAR(s.mean, 526.9, 0.05);
}

TEST(ImportersBasic, WalnutSixteenBitLittleEndian)
{
    const Volume v = test::import(test::shared_data("walnut/walnut.nhdr"));
    ASSERT_EQ(v.type(), ARBOR_VOXEL_U16);
    expect_dims(v, 128, 96, 114);
    expect_unit_geometry(v);
    const auto raw = read_bytes(test::shared_data("walnut/walnut.raw"));
    expect_voxels(v, decode<uint16_t>(raw, 0, false, 128 * 96 * 114));
    const Stats s = stats<uint16_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 22526);
    EXPECT_NEAR(s.mean, 2050.9, 0.05);
}

TEST(ImportersBasic, BrainTumourGzipWithSpaceDirections)
{
    const fs::path path = test::shared_data("mr_brain_tumor_pyradiomics/brain1_image.nrrd");
    const Volume v = test::import(path);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_I16);
    expect_dims(v, 256, 256, 25);
    EXPECT_NEAR(v.geometry().spacing[0], 0.78125, 1e-12);
    EXPECT_NEAR(v.geometry().spacing[1], 0.78125, 1e-12);
    EXPECT_NEAR(v.geometry().spacing[2], 6.5, 1e-12);
    // The y axis runs anterior: column 1 of the direction matrix is (0,-1,0).
    expect_direction(v, {1, 0, 0, 0, -1, 0, 0, 0, 1});
    EXPECT_NEAR(v.geometry().origin[0], -99.609375, 1e-9);
    EXPECT_NEAR(v.geometry().origin[1], 99.609375, 1e-9);
    EXPECT_NEAR(v.geometry().origin[2], -78.0, 1e-9);

    const auto file = read_bytes(path);
    const std::size_t data = offset_after(file, "\n\n");
    EXPECT_EQ(data, 406u); // the README's header size
    const auto decoded = inflate_all(file.data() + data, file.size() - data);
    expect_voxels(v, decode<int16_t>(decoded, 0, false, 256 * 256 * 25));
    const Stats s = stats<int16_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 3057);
    EXPECT_NEAR(s.mean, 385.7, 0.05);
}

TEST(ImportersBasic, BrainTumourLabelIsInt32ZeroOne)
{
    const fs::path path = test::shared_data("mr_brain_tumor_pyradiomics/brain1_label.nrrd");
    const Volume v = test::import(path);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_I32);
    expect_dims(v, 256, 256, 25);
    expect_direction(v, {1, 0, 0, 0, -1, 0, 0, 0, 1});
    const auto file = read_bytes(path);
    const std::size_t data = offset_after(file, "\n\n");
    EXPECT_EQ(data, 404u);
    const auto decoded = inflate_all(file.data() + data, file.size() - data);
    expect_voxels(v, decode<int32_t>(decoded, 0, false, 256 * 256 * 25));
    const Stats s = stats<int32_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 1);
    EXPECT_GT(s.mean, 0.0);
}

TEST(ImportersBasic, ChestCtMetaImageZlib)
{
    const fs::path path = test::shared_data("ct_chest_lidc2/LIDC2.mha");
    const Volume v = test::import(path);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 256, 256, 133);
    EXPECT_NEAR(v.geometry().spacing[0], 1.40625, 1e-9);
    EXPECT_NEAR(v.geometry().spacing[1], 1.40625, 1e-9);
    EXPECT_NEAR(v.geometry().spacing[2], 2.5, 1e-9);
    // TransformMatrix "1 a b  c -1 d  0 0 -1" lists the direction of each
    // grid axis in turn (ITK): axis 0 along +L, axis 1 along -P (anterior),
    // axis 2 along -S (inferior), as AnatomicalOrientation RPS says.
    expect_direction(v, {1, 0, 0, 0, -1, 0, 0, 0, -1}, 1e-12);
    EXPECT_NEAR(v.geometry().origin[0], 0.0, 1e-9);
    EXPECT_NEAR(v.geometry().origin[1], 360.0, 1e-9);
    EXPECT_NEAR(v.geometry().origin[2], 332.5, 1e-9);

    const auto file = read_bytes(path);
    const std::size_t data = offset_after(file, "ElementDataFile = LOCAL\n");
    EXPECT_EQ(data, 517u); // the README's header size
    const auto decoded = inflate_all(file.data() + data, file.size() - data);
    expect_voxels(v, decode<uint8_t>(decoded, 0, false, 256 * 256 * 133));
    const Stats s = stats<uint8_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 255);
    EXPECT_NEAR(s.mean, 7.1, 0.05);
}

TEST(ImportersBasic, HeadMrMetaImageDetached)
{
    const Volume v = test::import(test::shared_data("mr_head_lowres/HeadMRVolume.mhd"));
    ASSERT_EQ(v.type(), ARBOR_VOXEL_U8);
    expect_dims(v, 48, 62, 42);
    for (int a = 0; a < 3; ++a) {
        EXPECT_DOUBLE_EQ(v.geometry().spacing[a], 4.0);
        EXPECT_DOUBLE_EQ(v.geometry().origin[a], 0.0);
    }
    expect_direction(v, kIdentity, 0.0);
    expect_voxels(v, read_bytes(test::shared_data("mr_head_lowres/HeadMRVolume.raw")));
    const Stats s = stats<uint8_t>(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 255);
    EXPECT_NEAR(s.mean, 24.5, 0.05);
}

TEST(ImportersBasic, RawImporterWithExplicitParameters)
{
    const fs::path walnut = test::shared_data("walnut/walnut.raw");
    const Volume w = test::import(walnut, kRaw,
                                  {{"dims", "128,96,114"},
                                   {"type", "u16"},
                                   {"endian", "little"},
                                   {"spacing", "0.5,0.25,2"},
                                   {"origin", "1,-2,3"}});
    ASSERT_EQ(w.type(), ARBOR_VOXEL_U16);
    expect_dims(w, 128, 96, 114);
    EXPECT_DOUBLE_EQ(w.geometry().spacing[0], 0.5);
    EXPECT_DOUBLE_EQ(w.geometry().spacing[1], 0.25);
    EXPECT_DOUBLE_EQ(w.geometry().spacing[2], 2.0);
    EXPECT_DOUBLE_EQ(w.geometry().origin[1], -2.0);
    expect_direction(w, kIdentity, 0.0);
    expect_voxels(w, decode<uint16_t>(read_bytes(walnut), 0, false, 128 * 96 * 114));

    const fs::path tooth = test::shared_data("tooth16_bigendian/tooth.raw");
    const Volume t =
        test::import(tooth, kRaw, {{"dims", "103,94,161"}, {"type", "u16"}, {"endian", "big"}});
    expect_dims(t, 103, 94, 161);
    expect_unit_geometry(t);
    expect_voxels(t, decode<uint16_t>(read_bytes(tooth), 0, true, 103 * 94 * 161));
    const Stats s = stats<uint16_t>(t);
    EXPECT_EQ(s.max, 1300);
    EXPECT_NEAR(s.mean, 526.9, 0.05);
}

TEST(ImportersBasic, RawImporterHeaderOffsetAndFloatTypes)
{
    const fs::path dir = test::scratch_dir();
    std::vector<uint8_t> bytes(13, 0xee); // a 13-byte header to skip
    const double values[] = {-1.5, 0.0, 2.25, 1e300, -7.0, 3.5};
    for (double d : values) {
        uint8_t b[8];
        std::memcpy(b, &d, 8);
        append(bytes, std::rbegin(b), std::rend(b)); // big endian
    }
    const fs::path path = write_file(dir / "doubles.dat", "", bytes);
    const Volume v = test::import(
        path, "", {{"dims", "3,2,1"}, {"type", "f64"}, {"endian", "big"}, {"header-offset", "13"}});
    ASSERT_EQ(v.type(), ARBOR_VOXEL_F64);
    expect_voxels(v, std::vector<double>(std::begin(values), std::end(values)));
}

TEST(ImportersBasic, ImporterChoiceByProbing)
{
    const PluginRegistry &registry = test::built_plugins();
    EXPECT_EQ(choose_importer(registry, test::shared_data("nucleon/nucleon.nrrd")), kNrrd);
    EXPECT_EQ(choose_importer(registry, test::shared_data("tooth/tooth.nhdr")), kNrrd);
    EXPECT_EQ(choose_importer(registry,
                              test::shared_data("mr_brain_tumor_pyradiomics/brain1_image.nrrd")),
              kNrrd);
    EXPECT_EQ(choose_importer(registry, test::shared_data("ct_chest_lidc2/LIDC2.mha")), kMetaImage);
    EXPECT_EQ(choose_importer(registry, test::shared_data("mr_head_lowres/HeadMRVolume.mhd")),
              kMetaImage);
    EXPECT_EQ(choose_importer(registry, test::shared_data("walnut/walnut.raw")), kRaw);

    // Content wins over the suffix: a NRRD header named .raw is still NRRD.
    const fs::path dir = test::scratch_dir();
    const fs::path disguised = write_file(
        dir / "disguised.raw", kU8Header + "sizes: 2 2 2\nencoding: raw\n\n", counting_bytes(8));
    const auto ranked = rank_importers(registry, disguised);
    ASSERT_FALSE(ranked.empty());
    EXPECT_EQ(ranked.front().id, kNrrd);
    EXPECT_EQ(ranked.front().confidence, 100);
    expect_voxels(test::import(disguised), counting_bytes(8));
}

// ---- NRRD features on generated files -----------------------------------------

TEST(ImportersBasic, NrrdRasSpaceBecomesLps)
{
    const fs::path dir = test::scratch_dir();
    std::vector<uint8_t> data;
    std::vector<int16_t> expected;
    for (int i = 0; i < 2 * 3 * 4; ++i) {
        const int16_t value = static_cast<int16_t>(i * 1000 - 9000);
        expected.push_back(value);
        data.push_back(static_cast<uint8_t>(static_cast<uint16_t>(value) >> 8));
        data.push_back(static_cast<uint8_t>(value & 0xff));
    }
    const fs::path path = write_file(dir / "ras.nrrd",
                                     "NRRD0005\n# a comment\ntype: signed short int\ndimension: 3\n"
                                     "space: right-anterior-superior\nsizes: 2 3 4\n"
                                     "space directions: (0.5,0,0) (0,2,0) (0,0,-3)\n"
                                     "space origin: (10,20,30)\nkinds: domain domain domain\n"
                                     "endian: big\nencoding: raw\nsome future field: 42\n"
                                     "arbor_value_scale:=0.5\narbor_value_offset:=-1024\n"
                                     "arbor_value_unit:=HU\n\n",
                                     data);
    const Volume v = test::import(path);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_I16);
    expect_dims(v, 2, 3, 4);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[0], 0.5);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[1], 2.0);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[2], 3.0);
    // RAS x and y point the other way in LPS; z (superior) stays.
    expect_direction(v, {-1, 0, 0, 0, -1, 0, 0, 0, -1});
    EXPECT_DOUBLE_EQ(v.geometry().origin[0], -10.0);
    EXPECT_DOUBLE_EQ(v.geometry().origin[1], -20.0);
    EXPECT_DOUBLE_EQ(v.geometry().origin[2], 30.0);
    EXPECT_DOUBLE_EQ(v.mapping().scale, 0.5);
    EXPECT_DOUBLE_EQ(v.mapping().offset, -1024.0);
    EXPECT_EQ(v.mapping().unit, "HU");
    expect_voxels(v, expected);

    // The short codes and other frames.
    const fs::path las = write_file(
        dir / "las.nhdr", "NRRD0004\ntype: uchar\ndimension: 3\nspace: LAS\nsizes: 2 2 2\n"
                          "space directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (1,2,3)\n"
                          "encoding: raw\ndata file: las.raw\n");
    write_file(dir / "las.raw", "", counting_bytes(8));
    const Volume l = test::import(las);
    expect_direction(l, {1, 0, 0, 0, -1, 0, 0, 0, 1});
    EXPECT_DOUBLE_EQ(l.geometry().origin[1], -2.0);
}

TEST(ImportersBasic, NrrdSpaceDimensionWithoutSpaceIsLps)
{
    const fs::path dir = test::scratch_dir();
    const fs::path path = write_file(dir / "lps.nrrd",
                                     kU8Header + "space dimension: 3\nsizes: 2 2 2\n"
                                                 "space directions: (0,3,0) (-2,0,0) (0,0,1.5)\n"
                                                 "space origin: (-5,6,7)\nencoding: raw\n\n",
                                     counting_bytes(8));
    const Volume v = test::import(path);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[0], 3.0);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[1], 2.0);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[2], 1.5);
    expect_direction(v, {0, -1, 0, 1, 0, 0, 0, 0, 1});
    EXPECT_DOUBLE_EQ(v.geometry().origin[0], -5.0);
    EXPECT_DOUBLE_EQ(v.geometry().origin[2], 7.0);
}

TEST(ImportersBasic, NrrdEveryTypeSpelling)
{
    const fs::path dir = test::scratch_dir();
    const std::pair<const char *, arbor_voxel_type> spellings[] = {
        {"uchar", ARBOR_VOXEL_U8},
        {"unsigned char", ARBOR_VOXEL_U8},
        {"uint8", ARBOR_VOXEL_U8},
        {"uint8_t", ARBOR_VOXEL_U8},
        {"signed char", ARBOR_VOXEL_I8},
        {"int8", ARBOR_VOXEL_I8},
        {"int8_t", ARBOR_VOXEL_I8},
        {"short", ARBOR_VOXEL_I16},
        {"short int", ARBOR_VOXEL_I16},
        {"signed short", ARBOR_VOXEL_I16},
        {"signed short int", ARBOR_VOXEL_I16},
        {"int16", ARBOR_VOXEL_I16},
        {"int16_t", ARBOR_VOXEL_I16},
        {"ushort", ARBOR_VOXEL_U16},
        {"unsigned short", ARBOR_VOXEL_U16},
        {"unsigned short int", ARBOR_VOXEL_U16},
        {"uint16", ARBOR_VOXEL_U16},
        {"uint16_t", ARBOR_VOXEL_U16},
        {"int", ARBOR_VOXEL_I32},
        {"signed int", ARBOR_VOXEL_I32},
        {"int32", ARBOR_VOXEL_I32},
        {"int32_t", ARBOR_VOXEL_I32},
        {"uint", ARBOR_VOXEL_U32},
        {"unsigned int", ARBOR_VOXEL_U32},
        {"uint32", ARBOR_VOXEL_U32},
        {"uint32_t", ARBOR_VOXEL_U32},
        {"float", ARBOR_VOXEL_F32},
        {"double", ARBOR_VOXEL_F64},
    };
    int n = 0;
    for (const auto &[name, type] : spellings) {
        SCOPED_TRACE(name);
        const fs::path path =
            write_file(dir / ("t" + std::to_string(n++) + ".nrrd"),
                       std::string("NRRD0004\ntype: ") + name +
                           "\ndimension: 3\nsizes: 2 1 1\nencoding: ascii\n\n1 2\n");
        const Volume v = test::import(path);
        EXPECT_EQ(v.type(), type);
        EXPECT_EQ(v.value(0), 1.0);
        EXPECT_EQ(v.value(1), 2.0);
    }
}

TEST(ImportersBasic, NrrdAsciiTwoDimensionsAndLineSkip)
{
    const fs::path dir = test::scratch_dir();
    write_file(dir / "slice.txt",
               "this line is skipped\nand this one\n1.5 -2, 3e2\n4\t5\n   -6.25\nextra");
    const fs::path path = write_file(
        dir / "slice.nhdr", "NRRD0004\ntype: float\ndimension: 2\nsizes: 3 2\nspacings: 0.5 nan\n"
                            "encoding: text\nline skip: 2\ndata file: slice.txt\n");
    const Volume v = test::import(path);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_F32);
    expect_dims(v, 3, 2, 1);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[0], 0.5);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[1], 1.0);
    expect_voxels(v, std::vector<float>{1.5f, -2.0f, 300.0f, 4.0f, 5.0f, -6.25f});

    // Values that do not fit the type are an error, not a wrap-around.
    const fs::path big =
        write_file(dir / "big.nrrd", kU8Header + "sizes: 2 1 1\nencoding: ascii\n\n1 256\n");
    const std::string e = failure_of([&] { test::import(big); });
    EXPECT_MENTIONS(e, "'256'");
    EXPECT_MENTIONS(e, "not a u8 number");
}

TEST(ImportersBasic, NrrdByteSkipRawAndGzip)
{
    const fs::path dir = test::scratch_dir();
    const auto data = counting_bytes(4 * 4 * 4);
    // byte skip -1: the voxels are the last bytes, whatever lies before them.
    std::vector<uint8_t> padded(17, 0x55);
    append(padded, data.begin(), data.end());
    const fs::path at_end = write_file(
        dir / "end.nrrd", kU8Header + "sizes: 4 4 4\nencoding: raw\nbyte skip: -1\n\n", padded);
    expect_voxels(test::import(at_end), data);

    const fs::path skipped = write_file(
        dir / "skip.nrrd", kU8Header + "sizes: 4 4 4\nencoding: raw\nbyteskip: 17\n\n", padded);
    expect_voxels(test::import(skipped), data);

    // With gzip, the bytes are skipped after decompression.
    const fs::path gz =
        write_file(dir / "skip-gz.nrrd",
                   kU8Header + "sizes: 4 4 4\nencoding: gz\nbyte skip: 17\n\n", gzip_bytes(padded));
    expect_voxels(test::import(gz), data);

    // Two concatenated gzip members form one stream.
    auto two = gzip_bytes(std::vector<uint8_t>(data.begin(), data.begin() + 20));
    const auto second = gzip_bytes(std::vector<uint8_t>(data.begin() + 20, data.end()));
    append(two, second.begin(), second.end());
    const fs::path members =
        write_file(dir / "members.nrrd", kU8Header + "sizes: 4 4 4\nencoding: gzip\n\n", two);
    expect_voxels(test::import(members), data);
}

TEST(ImportersBasic, NrrdWrittenByArborReadsBack)
{
    const fs::path dir = test::scratch_dir();
    Geometry g;
    g.dims = {5, 4, 3};
    g.spacing = {0.7, 1.1, 2.5};
    g.origin = {-12.5, 3.25, 100.0};
    const double c = std::cos(0.3), s = std::sin(0.3);
    g.direction = {c, -s, 0, s, c, 0, 0, 0, 1};
    Volume original =
        Volume::allocate(ARBOR_VOXEL_I16, g, ValueMapping{1.0, -1024.0, "HU"}, 1 << 20);
    std::vector<int16_t> values;
    for (int64_t i = 0; i < original.voxel_count(); ++i) {
        original.as<int16_t>()[i] = static_cast<int16_t>(i * 37 - 1000);
        values.push_back(original.as<int16_t>()[i]);
    }
    for (bool gzip : {true, false}) {
        SCOPED_TRACE(gzip ? "gzip" : "raw");
        const fs::path path = dir / (gzip ? "round-gz.nrrd" : "round-raw.nrrd");
        io::NrrdWriteOptions options;
        options.gzip = gzip;
        io::write_nrrd(original, path, options);
        const Volume v = test::import(path);
        ASSERT_EQ(v.type(), ARBOR_VOXEL_I16);
        expect_dims(v, 5, 4, 3);
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(v.geometry().spacing[a], g.spacing[a], 1e-12);
            EXPECT_NEAR(v.geometry().origin[a], g.origin[a], 1e-12);
        }
        expect_direction(v, g.direction, 1e-12);
        EXPECT_DOUBLE_EQ(v.mapping().offset, -1024.0);
        EXPECT_EQ(v.mapping().unit, "HU");
        expect_voxels(v, values);
    }
}

// ---- MetaImage features on generated files ------------------------------------

TEST(ImportersBasic, MetaImageTransformMatrixListsAxisDirections)
{
    const fs::path dir = test::scratch_dir();
    std::vector<uint8_t> data;
    std::vector<int16_t> expected;
    for (int i = 0; i < 8; ++i) {
        const int16_t value = static_cast<int16_t>(-300 + i * 111);
        expected.push_back(value);
        data.push_back(static_cast<uint8_t>(static_cast<uint16_t>(value) >> 8));
        data.push_back(static_cast<uint8_t>(value & 0xff));
    }
    // Axis 0 runs along +P, axis 1 along -L (R), axis 2 along +S.
    const fs::path path = write_file(dir / "rotated.mha",
                                     "ObjectType = Image\nNDims = 3\nBinaryData = True\n"
                                     "BinaryDataByteOrderMSB = True\nCompressedData = False\n"
                                     "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = 1 2 3\n"
                                     "CenterOfRotation = 0 0 0\nAnatomicalOrientation = PRS\n"
                                     "ElementSpacing = 0.5 1 2\nDimSize = 2 2 2\n"
                                     "ElementType = MET_SHORT\nElementDataFile = LOCAL\n",
                                     data);
    const Volume v = test::import(path);
    ASSERT_EQ(v.type(), ARBOR_VOXEL_I16);
    expect_direction(v, {0, -1, 0, 1, 0, 0, 0, 0, 1});
    EXPECT_DOUBLE_EQ(v.geometry().spacing[0], 0.5);
    EXPECT_DOUBLE_EQ(v.geometry().spacing[2], 2.0);
    EXPECT_DOUBLE_EQ(v.geometry().origin[1], 2.0);
    expect_voxels(v, expected);
    // Voxel (1, 0, 0) lies 0.5 mm posterior of the origin.
    const auto p = v.geometry().position(1, 0, 0);
    EXPECT_NEAR(p[0], 1.0, 1e-12);
    EXPECT_NEAR(p[1], 2.5, 1e-12);
}

TEST(ImportersBasic, MetaImageStorageVariants)
{
    const fs::path dir = test::scratch_dir();
    const auto data = counting_bytes(3 * 4 * 5);

    // HeaderSize -1: the voxels are the last bytes of the data file.
    std::vector<uint8_t> padded(9, 0xaa);
    append(padded, data.begin(), data.end());
    write_file(dir / "tail.bin", "", padded);
    const fs::path tail = write_file(
        dir / "tail.mhd", "NDims = 3\nDimSize = 3 4 5\nElementType = MET_UCHAR\nHeaderSize = -1\n"
                          "ElementSize = 2 2 2\nElementDataFile = tail.bin\n");
    const Volume t = test::import(tail);
    expect_voxels(t, data);
    EXPECT_DOUBLE_EQ(t.geometry().spacing[1], 2.0); // ElementSize stands in for ElementSpacing

    // A positive HeaderSize counts from the start of the data file.
    const fs::path skip = write_file(
        dir / "skip.mhd", "NDims = 3\nDimSize = 3 4 5\nElementType = MET_CHAR\nHeaderSize = 9\n"
                          "ElementDataFile = tail.bin\n");
    const Volume k = test::import(skip);
    ASSERT_EQ(k.type(), ARBOR_VOXEL_I8);
    std::vector<int8_t> signed_data(data.begin(), data.end());
    expect_voxels(k, signed_data);

    // zlib without CompressedDataSize, and a gzip wrapper, both inflate.
    for (bool gz : {false, true}) {
        const fs::path z = write_file(dir / (gz ? "gz.mha" : "z.mha"),
                                      "NDims = 3\nDimSize = 3 4 5\nElementType = MET_UCHAR\n"
                                      "CompressedData = True\nElementDataFile = LOCAL\n",
                                      gz ? gzip_bytes(data) : zlib_bytes(data));
        expect_voxels(test::import(z), data);
    }

    // ASCII values, two dimensions as one slice.
    const fs::path text = write_file(
        dir / "text.mha", "NDims = 2\nDimSize = 2 3\nElementType = MET_FLOAT\nBinaryData = False\n"
                          "ElementSpacing = 0.25 0.5\nPosition = 4 5\nElementDataFile = LOCAL\n"
                          "1 2 3\n4 5 6.5\n");
    const Volume a = test::import(text);
    expect_dims(a, 2, 3, 1);
    EXPECT_DOUBLE_EQ(a.geometry().spacing[1], 0.5);
    EXPECT_DOUBLE_EQ(a.geometry().spacing[2], 1.0);
    EXPECT_DOUBLE_EQ(a.geometry().origin[0], 4.0);
    expect_voxels(a, std::vector<float>{1, 2, 3, 4, 5, 6.5f});

    // 32-bit and double element types, big endian.
    std::vector<uint8_t> be;
    for (uint32_t x : {1u, 70000u, 4000000000u})
        for (int k2 = 3; k2 >= 0; --k2)
            be.push_back(static_cast<uint8_t>(x >> (8 * k2)));
    const fs::path u32 = write_file(dir / "u32.mha",
                                    "NDims = 3\nDimSize = 3 1 1\nElementType = MET_UINT\n"
                                    "ElementByteOrderMSB = True\nElementDataFile = LOCAL\n",
                                    be);
    expect_voxels(test::import(u32), std::vector<uint32_t>{1u, 70000u, 4000000000u});
}

// ---- malformed input ------------------------------------------------------------

TEST(ImportersBasic, TruncatedDataIsReportedWithSizes)
{
    const fs::path dir = test::scratch_dir();
    write_file(dir / "short.raw", "", counting_bytes(1000));
    const fs::path detached =
        write_file(dir / "short.nhdr", kU8Header + "sizes: 64 64 64\nencoding: raw\n"
                                                   "data file: short.raw\n");
    std::string e = failure_of([&] { test::import(detached); });
    EXPECT_MENTIONS(e, "short.raw has 1000 bytes of voxel data");
    EXPECT_MENTIONS(e, "needs 262144");
    EXPECT_EQ(status_of([&] { test::import(detached); }), ARBOR_ERROR_FORMAT);

    const std::string header = kU8Header + "sizes: 64 64 64\nencoding: raw\n\n";
    const fs::path attached = write_file(dir / "short.nrrd", header, counting_bytes(100));
    e = failure_of([&] { test::import(attached); });
    EXPECT_MENTIONS(e, "short.nrrd has 100 bytes of voxel data from byte " +
                           std::to_string(header.size()));
    EXPECT_MENTIONS(e, "needs 262144");

    // The raw importer refuses in read_header, before the host allocates.
    e = failure_of([&] { test::import(dir / "short.raw", kRaw, {{"dims", "64,64,64"}}); });
    EXPECT_MENTIONS(e, "short.raw has 1000 bytes of voxel data");
    EXPECT_MENTIONS(e, "262144");
    EXPECT_MENTIONS(e, "reading the header");
    e = failure_of([&] {
        test::import(dir / "short.raw", kRaw, {{"dims", "10,10,10"}, {"header-offset", "1"}});
    });
    EXPECT_MENTIONS(e, "has 999 bytes of voxel data from byte 1 on");
    // Without a header, the file size is the only check of the parameters:
    // it must match exactly.
    e = failure_of([&] {
        test::import(test::shared_data("walnut/walnut.raw"), kRaw,
                     {{"dims", "128,96,113"}, {"type", "u16"}});
    });
    EXPECT_MENTIONS(e, "walnut.raw has 2801664 bytes of voxel data");
    EXPECT_MENTIONS(e, "need exactly 2777088 (check dims, type and header offset)");
    // Huge dims from parameters are caught by the same check.
    e = failure_of([&] {
        test::import(dir / "short.raw", kRaw, {{"dims", "100000,100000,100000"}});
    });
    EXPECT_MENTIONS(e, "need 1000000000000000");
}

TEST(ImportersBasic, BadSizesAreRefused)
{
    const fs::path dir = test::scratch_dir();
    const auto sized = [&](const std::string &name, const std::string &sizes) {
        return write_file(dir / name, kU8Header + "sizes: " + sizes + "\nencoding: raw\n\n",
                          counting_bytes(64));
    };
    for (const char *sizes : {"0 64 64", "-5 64 64"}) {
        const fs::path p = sized("bad.nrrd", sizes);
        const std::string e = failure_of([&] { test::import(p); });
        EXPECT_MENTIONS(e, std::string("sizes '") + sizes + "'");
        EXPECT_MENTIONS(e, "every size must be at least 1");
        EXPECT_EQ(status_of([&] { test::import(p); }), ARBOR_ERROR_FORMAT);
    }
    const fs::path overflow = sized("overflow.nrrd", "99999999999999999999 2 2");
    std::string e = failure_of([&] { test::import(overflow); });
    EXPECT_MENTIONS(e, "'99999999999999999999' is not a whole number that fits in 64 bits");

    const fs::path garbage = sized("words.nrrd", "64 sixty-four 64");
    e = failure_of([&] { test::import(garbage); });
    EXPECT_MENTIONS(e, "'sixty-four'");

    const fs::path count = sized("count.nrrd", "64 64");
    e = failure_of([&] { test::import(count); });
    EXPECT_MENTIONS(e, "has 2 numbers, but dimension is 3");

    // A header claiming 100000^3 voxels over a few bytes of data: refused at
    // the header, before any voxel memory exists, whatever the encoding.  The
    // importer sees that the file cannot hold the data (raw: too short; gzip:
    // beyond deflate's 1032:1 ratio).
    const std::map<std::string, std::string> reasons = {
        {"raw", "the header needs 1000000000000000"},
        {"gzip", "cannot expand to the 1000000000000000 bytes"}};
    for (const auto &[encoding, reason] : reasons) {
        const fs::path huge =
            write_file(dir / ("huge-" + encoding + ".nrrd"),
                       kU8Header + "sizes: 100000 100000 100000\nencoding: " + encoding + "\n\n",
                       gzip_bytes(counting_bytes(64)));
        e = failure_of([&] { test::import(huge); });
        EXPECT_MENTIONS(e, reason);
        EXPECT_EQ(status_of([&] { test::import(huge); }), ARBOR_ERROR_FORMAT);
    }
    // A detached header can point at a file that does hold the data: then
    // the host's own limit refuses the claim.
    const fs::path big_data = dir / "big.raw";
    {
        std::ofstream out(big_data, std::ios::binary);
        out.seekp(static_cast<std::streamoff>(uint64_t{1} << 33));
        out.put('\0'); // a sparse 8 GB file: no disk space used
    }
    const fs::path detached = write_file(dir / "huge.nhdr",
                                         kU8Header + "sizes: 2048 2048 512\nencoding: raw\n"
                                                     "data file: big.raw\n",
                                         {});
    e = failure_of([&] { test::import(detached, "", {}, uint64_t{1} << 30); });
    EXPECT_MENTIONS(e, "this host allows");
}

TEST(ImportersBasic, BadNrrdHeadersAreRefused)
{
    const fs::path dir = test::scratch_dir();
    struct Case {
        const char *name;
        std::string text;
        const char *words;
        arbor_status status;
    };
    const std::string tail = "sizes: 2 2 2\nencoding: raw\n\n" + std::string(64, 'x');
    const Case cases[] = {
        {"type.nrrd", "NRRD0004\ntype: quaternion\ndimension: 3\n" + tail,
         "type 'quaternion' is not a NRRD type", ARBOR_ERROR_FORMAT},
        {"int64.nrrd", "NRRD0004\ntype: long long\ndimension: 3\nendian: little\n" + tail,
         "64-bit integer voxels are not supported", ARBOR_ERROR_UNSUPPORTED},
        {"uint64.nrrd", "NRRD0004\ntype: uint64_t\ndimension: 3\nendian: little\n" + tail,
         "64-bit integer voxels are not supported", ARBOR_ERROR_UNSUPPORTED},
        {"block.nrrd", "NRRD0004\ntype: block\nblock size: 4\ndimension: 3\n" + tail, "'block'",
         ARBOR_ERROR_UNSUPPORTED},
        {"nosizes.nrrd", kU8Header + "encoding: raw\n\n", "has no 'sizes' field",
         ARBOR_ERROR_FORMAT},
        {"notype.nrrd", "NRRD0004\ndimension: 3\n" + tail, "has no 'type' field",
         ARBOR_ERROR_FORMAT},
        {"noencoding.nrrd", kU8Header + "sizes: 2 2 2\n\n", "has no 'encoding' field",
         ARBOR_ERROR_FORMAT},
        {"bzip2.nrrd", kU8Header + "sizes: 2 2 2\nencoding: bzip2\n\n",
         "encoding 'bzip2' is not supported", ARBOR_ERROR_UNSUPPORTED},
        {"hex.nrrd", kU8Header + "sizes: 2 2 2\nencoding: hex\n\n",
         "encoding 'hex' is not supported", ARBOR_ERROR_UNSUPPORTED},
        {"noendian.nrrd", "NRRD0004\ntype: uint16\ndimension: 3\n" + tail,
         "needs an 'endian' field", ARBOR_ERROR_FORMAT},
        {"dim4.nrrd",
         "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 2\nendian: little\nencoding: raw\n\n",
         "dimension 4", ARBOR_ERROR_UNSUPPORTED},
        {"vector.nrrd",
         "NRRD0004\ntype: uchar\ndimension: 3\nspace: RAS\nsizes: 3 2 2\n"
         "space directions: none (1,0,0) (0,1,0)\nencoding: raw\n\n",
         "axis 0 is 'none'", ARBOR_ERROR_UNSUPPORTED},
        {"rgb.nrrd",
         "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 2 2\nkinds: RGB-color domain "
         "domain\nencoding: raw\n\n",
         "axis 0 is 'RGB-color'", ARBOR_ERROR_UNSUPPORTED},
        {"time.nrrd", kU8Header + "space: right-anterior-superior-time\n" + tail, "has a time axis",
         ARBOR_ERROR_UNSUPPORTED},
        {"list.nhdr", kU8Header + "sizes: 2 2 2\nencoding: raw\ndata file: LIST\na.raw\nb.raw\n",
         "'data file: LIST'", ARBOR_ERROR_UNSUPPORTED},
        {"pattern.nhdr",
         kU8Header + "sizes: 2 2 2\nencoding: raw\ndata file: slice%03d.raw 1 2 1\n",
         "numbered files", ARBOR_ERROR_UNSUPPORTED},
        {"twice.nrrd", kU8Header + "sizes: 2 2 2\nsizes: 2 2 2\nencoding: raw\n\n", "appears twice",
         ARBOR_ERROR_FORMAT},
        {"noline.nrrd", kU8Header + "sizes: 2 2 2\nthis is not a field\nencoding: raw\n\n",
         "'this is not a field' is neither a field", ARBOR_ERROR_FORMAT},
        {"skip.nrrd", kU8Header + "sizes: 2 2 2\nencoding: gzip\nbyte skip: -1\n\n", "byte skip -1",
         ARBOR_ERROR_FORMAT},
        {"version.nrrd", "NRRD0009\ntype: uint8\ndimension: 3\n" + tail, "NRRD format version",
         ARBOR_ERROR_UNSUPPORTED},
        {"origin.nrrd", kU8Header + "space: LPS\nspace origin: (1,2)\n" + tail,
         "needs 3 components", ARBOR_ERROR_FORMAT},
        {"direction.nrrd",
         kU8Header + "space: LPS\nspace directions: (1,0,0) (0,0,0) (0,0,1)\n" + tail,
         "direction of axis 1 is zero", ARBOR_ERROR_FORMAT},
        {"nodata.nrrd", kU8Header + "sizes: 2 2 2\nencoding: raw\n", "no blank line",
         ARBOR_ERROR_FORMAT},
        {"scale.nrrd", kU8Header + "arbor_value_scale:=lots\n" + tail, "arbor_value_scale",
         ARBOR_ERROR_FORMAT},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path p = write_file(dir / c.name, c.text);
        const std::string e = failure_of([&] { test::import(p, kNrrd); });
        EXPECT_MENTIONS(e, c.name);
        EXPECT_MENTIONS(e, c.words);
        EXPECT_EQ(status_of([&] { test::import(p, kNrrd); }), c.status);
    }
}

TEST(ImportersBasic, MissingFilesAreIoErrors)
{
    const fs::path dir = test::scratch_dir();
    const fs::path header = write_file(
        dir / "orphan.nhdr", kU8Header + "sizes: 2 2 2\nencoding: raw\ndata file: gone.raw\n");
    const std::string e = failure_of([&] { test::import(header); });
    EXPECT_MENTIONS(e, "data file 'gone.raw' named in the header of orphan.nhdr does not exist");
    EXPECT_EQ(status_of([&] { test::import(header); }), ARBOR_ERROR_IO);

    const fs::path mhd = write_file(
        dir / "orphan.mhd",
        "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = gone.raw\n");
    EXPECT_MENTIONS(failure_of([&] { test::import(mhd); }), "'gone.raw'");
    EXPECT_EQ(status_of([&] { test::import(dir / "absent.nrrd", kNrrd); }), ARBOR_ERROR_IO);
    EXPECT_EQ(status_of([&] {
                  test::import(dir / "absent.raw", kRaw, {{"dims", "1,1,1"}});
              }),
              ARBOR_ERROR_IO);
}

TEST(ImportersBasic, BrokenGzipStreams)
{
    const fs::path dir = test::scratch_dir();
    const auto data = counting_bytes(32 * 32 * 32);
    const auto gz = gzip_bytes(data);
    const std::string header = kU8Header + "sizes: 32 32 32\nencoding: gzip\n\n";

    // A valid gzip header followed by bytes that are no deflate stream.
    std::vector<uint8_t> corrupt(210, 0xff);
    std::copy(gz.begin(), gz.begin() + 10, corrupt.begin());
    const fs::path bad = write_file(dir / "corrupt.nrrd", header, corrupt);
    std::string e = failure_of([&] { test::import(bad); });
    EXPECT_MENTIONS(e, "the gzip data of corrupt.nrrd is corrupt");
    EXPECT_EQ(status_of([&] { test::import(bad); }), ARBOR_ERROR_FORMAT);

    // The stream is cut in half: the message says how far it got.
    const fs::path cut = write_file(dir / "cut.nrrd", header,
                                    std::vector<uint8_t>(gz.begin(), gz.begin() + gz.size() / 2));
    e = failure_of([&] { test::import(cut); });
    EXPECT_MENTIONS(e, "the gzip data of cut.nrrd ends after ");
    EXPECT_MENTIONS(e, "decoded bytes of voxel data, the header needs 32768");

    // A stream whose checksum does not match its content.
    std::vector<uint8_t> wrong_crc = gz;
    wrong_crc[wrong_crc.size() - 6] ^= 0x5a;
    const fs::path crc = write_file(dir / "crc.nrrd", header, wrong_crc);
    e = failure_of([&] { test::import(crc); });
    EXPECT_MENTIONS(e, "crc.nrrd is corrupt");

    // MetaImage's CompressedDataSize bounds the stream.
    const auto z = zlib_bytes(data);
    const fs::path mha =
        write_file(dir / "cut.mha",
                   "NDims = 3\nDimSize = 32 32 32\nElementType = MET_UCHAR\nCompressedData = True\n"
                   "CompressedDataSize = 100\nElementDataFile = LOCAL\n",
                   z);
    e = failure_of([&] { test::import(mha); });
    EXPECT_MENTIONS(e, "the zlib data of cut.mha ends after");
}

TEST(ImportersBasic, GarbageAndEmptyFilesAreRefused)
{
    const fs::path dir = test::scratch_dir();
    std::vector<uint8_t> noise(8192);
    uint32_t x = 12345;
    for (auto &b : noise) {
        x = x * 1664525u + 1013904223u;
        b = static_cast<uint8_t>(x >> 24);
    }
    const std::pair<const char *, const char *> cases[] = {
        {"noise.nrrd", "noise.nrrd is not a NRRD file"},
        {"noise.nhdr", "noise.nhdr is not a NRRD file"},
        {"empty.nrrd", "empty.nrrd is empty"},
        {"noise.mha", "header of noise.mha: line 1"},
        {"empty.mhd", "empty.mhd is empty"},
    };
    for (const auto &[name, words] : cases) {
        SCOPED_TRACE(name);
        const bool empty = std::string(name).starts_with("empty");
        const fs::path p = write_file(dir / name, "", empty ? std::vector<uint8_t>{} : noise);
        EXPECT_MENTIONS(failure_of([&] { test::import(p); }), words);
        EXPECT_EQ(status_of([&] { test::import(p); }), ARBOR_ERROR_FORMAT);
    }
    // A NRRD magic followed by noise.
    std::vector<uint8_t> magic_noise = noise;
    std::memcpy(magic_noise.data(), "NRRD0004\n", 9);
    const fs::path p = write_file(dir / "magic.nrrd", "", magic_noise);
    EXPECT_EQ(status_of([&] { test::import(p); }), ARBOR_ERROR_FORMAT);
}

TEST(ImportersBasic, BadMetaImageHeadersAreRefused)
{
    const fs::path dir = test::scratch_dir();
    struct Case {
        const char *name;
        std::string text;
        const char *words;
        arbor_status status;
    };
    const std::string tail =
        "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + std::string(64, 'x');
    const Case cases[] = {
        {"ndims4.mha", "NDims = 4\nDimSize = 2 2 2 2\n" + tail, "NDims 4", ARBOR_ERROR_UNSUPPORTED},
        {"channels.mha", "NDims = 3\nDimSize = 2 2 2\nElementNumberOfChannels = 3\n" + tail,
         "ElementNumberOfChannels 3", ARBOR_ERROR_UNSUPPORTED},
        {"nodims.mha", "NDims = 3\n" + tail, "has no DimSize line", ARBOR_ERROR_FORMAT},
        {"nondims.mha", "DimSize = 2 2 2\n" + tail, "has no NDims line", ARBOR_ERROR_FORMAT},
        {"dimcount.mha", "NDims = 3\nDimSize = 2 2\n" + tail, "has 2 numbers, but NDims is 3",
         ARBOR_ERROR_FORMAT},
        {"zero.mha", "NDims = 3\nDimSize = 2 0 2\n" + tail, "every size must be at least 1",
         ARBOR_ERROR_FORMAT},
        {"huge.mha", "NDims = 3\nDimSize = 2 99999999999999999999 2\n" + tail,
         "'99999999999999999999'", ARBOR_ERROR_FORMAT},
        {"long.mha",
         "NDims = 3\nDimSize = 2 2 2\nElementType = MET_LONG_LONG\nElementDataFile = LOCAL\n",
         "ElementType 'MET_LONG_LONG' is not supported", ARBOR_ERROR_UNSUPPORTED},
        {"type.mha", "NDims = 3\nDimSize = 2 2 2\nElementType = pixels\nElementDataFile = LOCAL\n",
         "'pixels' is not a MetaImage element type", ARBOR_ERROR_FORMAT},
        {"notype.mha", "NDims = 3\nDimSize = 2 2 2\nElementDataFile = LOCAL\n",
         "has no ElementType line", ARBOR_ERROR_FORMAT},
        {"nofile.mha", "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n",
         "has no ElementDataFile line", ARBOR_ERROR_FORMAT},
        {"list.mhd",
         "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = LIST 2D\na.raw\n",
         "'ElementDataFile = LIST'", ARBOR_ERROR_UNSUPPORTED},
        {"spacing.mha", "NDims = 3\nDimSize = 2 2 2\nElementSpacing = 1 -1 1\n" + tail,
         "every spacing must be positive", ARBOR_ERROR_FORMAT},
        {"matrix.mha", "NDims = 3\nDimSize = 2 2 2\nTransformMatrix = 1 0 0 0 1 0\n" + tail,
         "is not 9 numbers", ARBOR_ERROR_FORMAT},
        {"msb.mha", "NDims = 3\nDimSize = 2 2 2\nElementByteOrderMSB = maybe\n" + tail,
         "neither True nor False", ARBOR_ERROR_FORMAT},
        {"object.mha", "ObjectType = Mesh\nNDims = 3\nDimSize = 2 2 2\n" + tail,
         "ObjectType 'Mesh'", ARBOR_ERROR_UNSUPPORTED},
        {"line.mha", "NDims = 3\nDimSize 2 2 2\n" + tail, "is not a 'Key = Value' line",
         ARBOR_ERROR_FORMAT},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path p = write_file(dir / c.name, c.text);
        const std::string e = failure_of([&] { test::import(p, kMetaImage); });
        EXPECT_MENTIONS(e, c.name);
        EXPECT_MENTIONS(e, c.words);
        EXPECT_EQ(status_of([&] { test::import(p, kMetaImage); }), c.status);
    }
    // Truncated MetaImage data.
    const fs::path shortfile = write_file(
        dir / "short.mha",
        "NDims = 3\nDimSize = 4 4 4\nElementType = MET_USHORT\nElementDataFile = LOCAL\n",
        counting_bytes(100));
    EXPECT_MENTIONS(failure_of([&] { test::import(shortfile); }), "has 100 bytes of voxel data");
}

TEST(ImportersBasic, RawImporterNeedsDims)
{
    const fs::path walnut = test::shared_data("walnut/walnut.raw");
    std::string e = failure_of([&] { test::import(walnut, kRaw); });
    EXPECT_MENTIONS(e, "headerless raw file walnut.raw needs parameter 'dims'");
    EXPECT_EQ(status_of([&] { test::import(walnut, kRaw); }), ARBOR_ERROR_INVALID_ARGUMENT);
    // Parameter values outside their description never reach the plugin.
    e = failure_of([&] { test::import(walnut, kRaw, {{"dims", "0,96,114"}}); });
    EXPECT_MENTIONS(e, "dims");
    e = failure_of([&] { test::import(walnut, kRaw, {{"dims", "128,96,114"}, {"type", "u64"}}); });
    EXPECT_MENTIONS(e, "type");
}

// ---- calls the host never makes, straight through the ABI ---------------------

TEST(ImportersBasic, ReadVoxelsChecksTheVolumeAgainstTheFile)
{
    const PluginRegistry &registry = test::built_plugins();
    PluginInstance importer = registry.create(kNrrd);
    const auto &table = importer.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
    const fs::path path = test::shared_data("nucleon/nucleon.nrrd");
    std::vector<uint8_t> buffer(8);
    arbor_volume v{};
    v.struct_size = sizeof v;
    v.voxel_type = ARBOR_VOXEL_U8;
    v.dims[0] = v.dims[1] = v.dims[2] = 2;
    v.strides[0] = 1;
    v.strides[1] = 2;
    v.strides[2] = 4;
    v.voxels = buffer.data();
    Task task;
    EXPECT_EQ(table.read_voxels(importer.get(), path.c_str(), task.get(), &v),
              ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT_MENTIONS(importer.last_error(), "is 2 x 2 x 2 u8, but the file holds 41 x 41 x 41 u8");
}

TEST(ImportersBasic, CancellationStopsReading)
{
    const PluginRegistry &registry = test::built_plugins();
    for (const char *file : {"walnut/walnut.nhdr", "mr_brain_tumor_pyradiomics/brain1_image.nrrd",
                             "ct_chest_lidc2/LIDC2.mha"}) {
        SCOPED_TRACE(file);
        const fs::path path = test::shared_data(file);
        PluginInstance importer = registry.create(choose_importer(registry, path));
        const auto &table = importer.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
        arbor_volume header{};
        header.struct_size = sizeof header;
        Task header_task;
        ASSERT_EQ(table.read_header(importer.get(), path.c_str(), header_task.get(), &header),
                  ARBOR_OK);
        Volume volume = Volume::allocate(header, uint64_t{1} << 30);
        arbor_volume target = volume.view();
        Task task;
        task.cancel();
        EXPECT_EQ(table.read_voxels(importer.get(), path.c_str(), task.get(), &target),
                  ARBOR_ERROR_CANCELLED);
    }
}

} // namespace
} // namespace arbor
