// Whether a volume's values are Hounsfield units, judged from the values:
// synthetic tissue mixtures with known shares and peaks.
#include "core/hounsfield_scale.hpp"
#include "core/volume.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace arbor {
namespace {

// A share of the voxels and how their HU values are drawn.
struct Tissue {
    double share;
    double low, high; // uniform in [low, high] when sd == 0
    double mean = 0.0, sd = 0.0;
};

std::vector<double> mixture(const std::vector<Tissue> &tissues, int64_t n, unsigned seed = 7)
{
    std::mt19937 rng(seed);
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(n));
    for (const Tissue &t : tissues) {
        const auto count = static_cast<int64_t>(std::llround(t.share * static_cast<double>(n)));
        std::normal_distribution<double> normal(t.mean, t.sd > 0 ? t.sd : 1.0);
        std::uniform_real_distribution<double> uniform(t.low, t.high);
        for (int64_t i = 0; i < count && static_cast<int64_t>(out.size()) < n; ++i)
            out.push_back(t.sd > 0 ? normal(rng) : uniform(rng));
    }
    while (static_cast<int64_t>(out.size()) < n)
        out.push_back(0.0);
    std::shuffle(out.begin(), out.end(), rng);
    return out;
}

// Stored = (hu - offset) / scale, rounded and clamped to the type.
template <class T>
Volume volume_of(const std::vector<double> &hu, arbor_voxel_type type, ValueMapping mapping)
{
    Geometry g;
    g.dims = {static_cast<int64_t>(hu.size()), 1, 1};
    Volume v = Volume::allocate(type, g, mapping, uint64_t{1} << 30);
    T *p = v.as<T>();
    for (std::size_t i = 0; i < hu.size(); ++i) {
        const double stored = (hu[i] - mapping.offset) / mapping.scale;
        if constexpr (std::is_floating_point_v<T>)
            p[i] = static_cast<T>(stored);
        else
            p[i] = static_cast<T>(std::clamp<double>(std::round(stored), std::numeric_limits<T>::min(),
                                                     std::numeric_limits<T>::max()));
    }
    return v;
}

// A head CT: air around it, soft tissue (brain), bone.
const std::vector<Tissue> kHead = {{0.55, 0, 0, -1000, 8}, {0.32, 0, 0, 35, 12}, {0.10, 300, 1800}, {0.03, -150, -50}};
// A chest CT cut close to the body: much lung, little air outside.
const std::vector<Tissue> kChest = {
    {0.02, 0, 0, -1000, 8}, {0.30, -900, -650}, {0.15, 0, 0, -100, 15}, {0.43, 0, 0, 45, 15}, {0.10, 250, 1500}};

TEST(HounsfieldScale, HeadCtInHuIsRecognisedWithItsPeaks)
{
    const Volume v = volume_of<int16_t>(mixture(kHead, 200000), ARBOR_VOXEL_I16, {});
    const auto e = infer_hounsfield(v);
    ASSERT_TRUE(e.has_value());
    EXPECT_NEAR(e->air_peak, -1000, 20);
    EXPECT_NEAR(e->tissue_peak, 35, 20);
    EXPECT_NEAR(e->air_fraction, 0.55, 0.01);
    EXPECT_GT(e->tissue_fraction, 0.32);
    EXPECT_NE(e->describe().find("55 % air"), std::string::npos) << e->describe();
}

TEST(HounsfieldScale, ChestCtWithMoreLungThanAirIsRecognised)
{
    const Volume v = volume_of<int16_t>(mixture(kChest, 200000), ARBOR_VOXEL_I16, {});
    const auto e = infer_hounsfield(v);
    ASSERT_TRUE(e.has_value());
    EXPECT_NEAR(e->air_peak, -1000, 20);
    EXPECT_NEAR(e->tissue_peak, 45, 30);
}

TEST(HounsfieldScale, TheMappingIsApplied)
{
    // Stored as unsigned with air at 0: HU only through the intercept.
    const std::vector<double> hu = mixture(kHead, 100000);
    const Volume with_offset = volume_of<uint16_t>(hu, ARBOR_VOXEL_U16, {1.0, -1024.0, ""});
    EXPECT_TRUE(infer_hounsfield(with_offset).has_value());
    ValueMapping none;
    std::vector<double> stored(hu.size());
    for (std::size_t i = 0; i < hu.size(); ++i)
        stored[i] = hu[i] + 1024.0;
    EXPECT_FALSE(infer_hounsfield(volume_of<uint16_t>(stored, ARBOR_VOXEL_U16, none)).has_value());
    // Float values, with some NaN, scaled by 2.
    std::vector<double> halves = hu;
    for (std::size_t i = 0; i < halves.size(); i += 97)
        halves[i] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(infer_hounsfield(volume_of<float>(halves, ARBOR_VOXEL_F32, {2.0, 0.0, ""})).has_value());
}

TEST(HounsfieldScale, OtherModalitiesAndFieldsAreNot)
{
    // An MR: background noise near 0, tissue 200 to 900.
    const Volume mr = volume_of<uint16_t>(
        mixture({{0.4, 0, 0, 20, 10}, {0.6, 200, 900}}, 100000), ARBOR_VOXEL_U16, {});
    EXPECT_FALSE(infer_hounsfield(mr).has_value());
    // A phase map: spread evenly over +-4096.
    const Volume phase = volume_of<int16_t>(mixture({{1.0, -4096, 4096}}, 100000), ARBOR_VOXEL_I16, {});
    EXPECT_FALSE(infer_hounsfield(phase).has_value());
    // Air, but nothing at soft tissue (the peak at 500).
    const Volume no_tissue = volume_of<int16_t>(
        mixture({{0.5, 0, 0, -1000, 8}, {0.5, 0, 0, 500, 30}}, 100000), ARBOR_VOXEL_I16, {});
    EXPECT_FALSE(infer_hounsfield(no_tissue).has_value());
    // Soft tissue, but no air: the body filling the field, padded at -3024.
    const Volume no_air = volume_of<int16_t>(
        mixture({{0.3, -3024, -3024}, {0.6, 0, 0, 40, 15}, {0.1, 300, 1200}}, 100000), ARBOR_VOXEL_I16, {});
    EXPECT_FALSE(infer_hounsfield(no_air).has_value());
    // Air displaced by 150 HU: not a calibrated CT.
    const Volume shifted = volume_of<int16_t>(
        mixture({{0.5, 0, 0, -850, 8}, {0.5, 0, 0, 185, 12}}, 100000), ARBOR_VOXEL_I16, {});
    EXPECT_FALSE(infer_hounsfield(shifted).has_value());
    EXPECT_FALSE(infer_hounsfield(Volume{}).has_value());
}

TEST(HounsfieldScale, LargeVolumesAreSampled)
{
    // 5.2 M voxels: read with a stride; the shares still hold to a percent.
    const Volume v = volume_of<int16_t>(mixture(kHead, 5200000), ARBOR_VOXEL_I16, {});
    const auto e = infer_hounsfield(v);
    ASSERT_TRUE(e.has_value());
    EXPECT_NEAR(e->air_fraction, 0.55, 0.01);
}

} // namespace
} // namespace arbor
