// The pieces the default image stands on, on volumes made to know the
// answer: the background level of a histogram, the thickness and
// compactness of labelled structures, the extrema count on a known field,
// the denoising study's plateau, CT tissue names, and framing.
#include "core/background_level.hpp"
#include "core/ct_tissue.hpp"
#include "core/volume.hpp"
#include "pipeline/auto_denoise.hpp"
#include "pipeline/framing.hpp"
#include "topology/critical_points.hpp"
#include "topology/label_thickness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace arbor {
namespace {

constexpr int64_t kN = 48;

Volume cube(arbor_voxel_type type, const std::function<double(int64_t, int64_t, int64_t)> &f)
{
    Geometry g;
    g.dims = {kN, kN, kN};
    Volume v = Volume::allocate(type, g, {}, uint64_t{1} << 30);
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t j = 0; j < kN; ++j)
            for (int64_t i = 0; i < kN; ++i) {
                const double x = f(i, j, k);
                const std::size_t at = static_cast<std::size_t>(i + kN * (j + kN * k));
                if (type == ARBOR_VOXEL_F32)
                    v.as<float>()[at] = static_cast<float>(x);
                else
                    v.as<int16_t>()[at] = static_cast<int16_t>(std::lround(x));
            }
    return v;
}

bool in_ball(int64_t i, int64_t j, int64_t k, double r)
{
    const double c = (kN - 1) / 2.0;
    return (i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c) < r * r;
}

TEST(BackgroundLevel, ACtsAirEndsWhereItsNoiseDoes)
{
    std::mt19937 rng(1);
    std::normal_distribution<double> noise(0.0, 15.0);
    // Air at -1000 HU around a ball of soft tissue at 40 with bone inside.
    const Volume v = cube(ARBOR_VOXEL_I16, [&](int64_t i, int64_t j, int64_t k) {
        const double base = in_ball(i, j, k, 10) ? 700 : in_ball(i, j, k, 20) ? 40 : -1000;
        return base + noise(rng);
    });
    const auto b = estimate_background(v);
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->peak, -1000, 10);
    EXPECT_GT(b->level, -1000 + 15);  // above the noise's bulk ...
    EXPECT_LT(b->level, -1000 + 100); // ... well below any tissue
    EXPECT_GT(b->fraction, 0.5);
}

TEST(BackgroundLevel, PaddingBelowTheAirDoesNotStopIt)
{
    std::mt19937 rng(2);
    std::normal_distribution<double> noise(0.0, 10.0);
    // -2000 outside a circular field of view, air inside it, a body with bone.
    const Volume v = cube(ARBOR_VOXEL_I16, [&](int64_t i, int64_t j, int64_t k) {
        const double c = (kN - 1) / 2.0;
        if ((i - c) * (i - c) + (j - c) * (j - c) > 23.0 * 23.0)
            return -2000.0;
        return (in_ball(i, j, k, 6) ? 1500.0 : in_ball(i, j, k, 14) ? 50.0 : -1000.0) + noise(rng);
    });
    const auto b = estimate_background(v);
    ASSERT_TRUE(b);
    EXPECT_GT(b->level, -1000); // the air is background too
    EXPECT_LT(b->level, -800);
}

TEST(BackgroundLevel, AScanCroppedInsideTheBodyHasNone)
{
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 10.0);
    const Volume v = cube(ARBOR_VOXEL_F32, [&](int64_t i, int64_t, int64_t) { return 40.0 + i + noise(rng); });
    EXPECT_FALSE(estimate_background(v));
}

TEST(LabelShapes, ThicknessOfASlabABallAndAShell)
{
    std::vector<uint32_t> labels(static_cast<std::size_t>(kN * kN * kN), 0);
    const double c = (kN - 1) / 2.0;
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t j = 0; j < kN; ++j)
            for (int64_t i = 0; i < kN; ++i) {
                const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
                uint32_t &l = labels[static_cast<std::size_t>(i + kN * (j + kN * k))];
                if (r < 8)
                    l = 1; // a ball of radius 8
                else if (r >= 18 && r < 20)
                    l = 2; // a shell 2 thick
                else if (k >= 1 && k < 5)
                    l = 3; // a slab 4 thick
            }
    const auto s = topology::label_shapes(labels, {kN, kN, kN}, {1, 1, 1}, 4);
    EXPECT_NEAR(s[1].thickness_mm, 2.0 * 8 / 3, 0.2 * 2.0 * 8 / 3);
    EXPECT_NEAR(s[2].thickness_mm, 2.0, 0.5);
    EXPECT_NEAR(s[3].thickness_mm, 4.0 * 1.5, 1.5); // flat faces are not staircases: 1.5 too thick
    EXPECT_GT(s[1].compactness, 0.3);                // a ball
    EXPECT_LT(s[2].compactness, 0.2);                // a shell
    // Spacing scales thickness, not compactness.
    const auto t = topology::label_shapes(labels, {kN, kN, kN}, {2, 2, 2}, 4);
    EXPECT_NEAR(t[1].thickness_mm, 2 * s[1].thickness_mm, 1e-9);
    EXPECT_NEAR(t[1].compactness, s[1].compactness, 1e-9);
}

TEST(CriticalPoints, TwoBumpsAndAPit)
{
    // Two Gaussian bumps and a pit on a tilted plane: the grid's only
    // interior extrema; the plane's low corner is the global minimum.
    const Volume v = cube(ARBOR_VOXEL_F32, [](int64_t i, int64_t j, int64_t k) {
        const auto g = [&](double x, double y, double z) {
            return std::exp(-((i - x) * (i - x) + (j - y) * (j - y) + (k - z) * (k - z)) / 18.0);
        };
        return 100 * g(12, 12, 24) + 80 * g(36, 36, 24) - 60 * g(24, 36, 12) + 0.01 * (i + j + k);
    });
    const topology::ExtremumCount c = topology::count_extrema(ARBOR_VOXEL_F32, v.data(), kN, kN, kN);
    EXPECT_EQ(c.maxima, 3u); // two bumps and the plane's high corner
    EXPECT_EQ(c.minima, 2u); // the pit and the plane's low corner
    EXPECT_EQ(c.branches(), 4u);
}

TEST(DenoisingStudy, ThePlateauIsWhereStepsStopPayingOff)
{
    // Steep drops, then one a fifth as steep or less: the plateau is there.
    EXPECT_EQ(pipeline::plateau_index({100000, 30000, 5000, 4000, 3500}), 2u);
    EXPECT_EQ(pipeline::plateau_index({1000, 999, 998}), 2u); // every step alike: none pays off less, the last
    EXPECT_EQ(pipeline::plateau_index({1000, 100, 10}), 2u);  // never flattens: the last
}

TEST(DenoisingStudy, ASmoothScanIsLeftAlone)
{
    const Volume v = cube(ARBOR_VOXEL_F32, [](int64_t i, int64_t j, int64_t k) {
        return std::sin(i / 7.0) + std::cos(j / 9.0) + k / 50.0;
    });
    bool smoothed = false;
    const pipeline::DenoiseAdvice a = pipeline::advise_denoising(v, [&](const Volume &x, double) {
        smoothed = true;
        return Volume::allocate(x.type(), x.geometry(), {}, uint64_t{1} << 30);
    });
    EXPECT_FALSE(a.noise_dominated);
    EXPECT_EQ(a.sigma_mm, 0.0);
    EXPECT_FALSE(smoothed);
}

TEST(CtTissues, RangesNameTheirTissues)
{
    EXPECT_EQ(ct_tissues_spanned(-1024, -1000), (std::vector<std::string>{"air"}));
    EXPECT_EQ(ct_tissues_spanned(20, 80), (std::vector<std::string>{"soft tissue"}));
    EXPECT_EQ(ct_tissues_spanned(-100, 60), (std::vector<std::string>{"fat", "soft tissue"}));
    EXPECT_EQ(ct_tissues_spanned(700, 1800), (std::vector<std::string>{"bone"}));
    EXPECT_EQ(ct_tissues_spanned(-1024, 3000).size(), 6u);
}

TEST(Framing, ContentOffCentreEndsUpCentredAndFilling)
{
    // A preview where a 20 x 10 pixel box in the upper left is opaque.
    RenderedImage preview;
    preview.width = preview.height = 100;
    preview.rgba.assign(100 * 100 * 4, 0.0f);
    for (int y = 10; y < 20; ++y)
        for (int x = 5; x < 25; ++x)
            preview.rgba[(static_cast<std::size_t>(y) * 100 + x) * 4 + 3] = 1.0f;
    arbor_camera c{};
    c.struct_size = sizeof c;
    c.projection = ARBOR_PROJECTION_ORTHOGRAPHIC;
    c.parallel_scale = 50; // the view spans [-50, 50] mm
    c.focal_point[2] = 0;
    c.position[2] = 300; // looking down -z, y up
    c.view_up[1] = 1;
    const auto f = pipeline::frame_content(c, preview, 100, 100, 0.85);
    ASSERT_TRUE(f);
    EXPECT_NEAR(f->content_fraction, 0.2, 1e-9);
    EXPECT_NEAR(f->scale, 0.85 / 0.2, 1e-9);
    // Looking down -z with y up, x points left... the box's centre in mm:
    // x = +/-(15 - 50), y = 50 - 15; the camera moves onto it.
    EXPECT_NEAR(std::fabs(f->camera.focal_point[0]), 35, 1e-6);
    EXPECT_NEAR(f->camera.focal_point[1], 35, 1e-6);
    EXPECT_NEAR(f->camera.parallel_scale, 50 / f->scale, 1e-9);
    // Nothing seen, nothing framed.
    std::fill(preview.rgba.begin(), preview.rgba.end(), 0.0f);
    EXPECT_FALSE(pipeline::frame_content(c, preview, 100, 100));
}

} // namespace
} // namespace arbor
