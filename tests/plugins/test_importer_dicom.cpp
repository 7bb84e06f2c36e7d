// The DICOM importer (org.arbor.importer.dicom) through the ABI on the shared
// DICOM series: choice by probing, geometry and values against the data sets'
// READMEs, series selection, progress and cancellation.  Voxel-by-voxel
// comparisons with pydicom are in integration/test_dicom.py.
#include "plugin_fixture.hpp"

#include "core/volume_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace arbor {
namespace {

namespace fs = std::filesystem;

constexpr const char *kDicom = "org.arbor.importer.dicom";

TEST(DicomImporter, IsChosenForDicomFilesAndFolders)
{
    const PluginRegistry &registry = test::built_plugins();
    EXPECT_EQ(choose_importer(registry, test::shared_data("dicom_mr_brain_vs_tumor")), kDicom);
    EXPECT_EQ(choose_importer(registry, test::shared_data("dicom_compressed_wg04/CT1_JPLL.dcm")), kDicom);
    const auto ranked = rank_importers(registry, test::shared_data("dicom_compressed_wg04/MR1_UNC.dcm"));
    ASSERT_FALSE(ranked.empty());
    EXPECT_EQ(ranked.front().id, kDicom);
    EXPECT_EQ(ranked.front().confidence, 100);
    // A folder of other formats is not DICOM.
    for (const ImporterChoice &c : rank_importers(registry, test::shared_data("tooth")))
        EXPECT_NE(c.id, kDicom);
}

TEST(DicomImporter, MrSeriesWithTumour)
{
    const Volume v = test::import(test::shared_data("dicom_mr_brain_vs_tumor"));
    const auto &g = v.geometry();
    EXPECT_EQ(g.dims, (std::array<int64_t, 3>{512, 512, 120}));
    EXPECT_EQ(v.type(), ARBOR_VOXEL_U16);
    EXPECT_NEAR(g.spacing[0], 0.41015625, 1e-9);
    EXPECT_NEAR(g.spacing[1], 0.41015625, 1e-9);
    EXPECT_NEAR(g.spacing[2], 1.5, 1e-4);
    EXPECT_NEAR(g.origin[2], -92.0, 0.01); // README: z = -92.0 .. 86.5 mm
    EXPECT_NEAR(g.origin[2] + 119 * g.spacing[2], 86.5, 0.01);
    for (int e = 0; e < 9; ++e)
        EXPECT_NEAR(g.direction[e], e % 4 == 0 ? 1.0 : 0.0, 1e-6);
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_EQ(s.min, 0);
    EXPECT_EQ(s.max, 1826);
    EXPECT_NEAR(s.mean, 204.6, 0.05);
}

TEST(DicomImporter, HeadCtInHounsfieldUnits)
{
    const Volume v = test::import(test::shared_data("dicom_ct_head_0051"));
    EXPECT_EQ(v.geometry().dims, (std::array<int64_t, 3>{512, 512, 108}));
    EXPECT_NEAR(v.geometry().spacing[0], 0.4785156, 1e-7);
    EXPECT_NEAR(v.geometry().origin[2], 116.0, 1e-3);
    EXPECT_NEAR(v.geometry().origin[2] + 107 * v.geometry().spacing[2], 276.0, 1e-3);
    EXPECT_EQ(v.mapping().scale, 1.0);
    EXPECT_EQ(v.mapping().offset, -1024.0);
    EXPECT_EQ(v.mapping().unit, "HU");
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_EQ(s.min * v.mapping().scale + v.mapping().offset, -1024); // README: HU -1024 .. 3033
    EXPECT_EQ(s.max * v.mapping().scale + v.mapping().offset, 3033);
}

TEST(DicomImporter, SeriesParameterPicksOneSeriesOfAFolder)
{
    const fs::path variants = test::shared_data("dicom_pydicom_variants");
    EXPECT_THROW(test::import(variants, kDicom), std::exception);
    const Volume ct = test::import(variants, kDicom, {{"series", "1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322"}});
    EXPECT_EQ(ct.geometry().dims, (std::array<int64_t, 3>{128, 128, 1}));
    const Volume emri = test::import(variants, kDicom, {{"series", "2"}});
    EXPECT_EQ(emri.geometry().dims, (std::array<int64_t, 3>{64, 64, 10}));
    try {
        test::import(variants, kDicom, {{"series", "42"}});
        FAIL() << "an unknown series was accepted";
    } catch (const std::exception &e) {
        EXPECT_NE(std::string(e.what()).find("no series '42'"), std::string::npos) << e.what();
    }
}

class RecordingSink : public ProgressSink {
public:
    void report(const std::string &, double fraction) override { fractions.push_back(fraction); }
    void finish() override {}
    std::vector<double> fractions;
};

TEST(DicomImporter, ReportsProgressAndHonoursCancellation)
{
    const fs::path path = test::shared_data("dicom_ct_head_0051");
    PluginInstance importer = test::built_plugins().create(kDicom);
    const auto &table = importer.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
    arbor_volume header{};
    header.struct_size = sizeof header;
    {
        Task task;
        ASSERT_EQ(table.read_header(importer.get(), path.c_str(), task.get(), &header), ARBOR_OK)
            << importer.last_error();
    }
    Volume volume = Volume::allocate(header, uint64_t{1} << 32);
    arbor_volume target = volume.view();
    RecordingSink sink;
    {
        Task task(&sink);
        ASSERT_EQ(table.read_voxels(importer.get(), path.c_str(), task.get(), &target), ARBOR_OK)
            << importer.last_error();
    }
    ASSERT_GE(sink.fractions.size(), 108u);
    EXPECT_DOUBLE_EQ(sink.fractions.back(), 1.0);
    for (std::size_t i = 1; i < sink.fractions.size(); ++i)
        EXPECT_GE(sink.fractions[i], sink.fractions[i - 1]);

    Task cancelled;
    cancelled.cancel();
    EXPECT_EQ(table.read_voxels(importer.get(), path.c_str(), cancelled.get(), &target), ARBOR_ERROR_CANCELLED);
    EXPECT_NE(importer.last_error().find("cancelled"), std::string::npos);
}

} // namespace
} // namespace arbor
