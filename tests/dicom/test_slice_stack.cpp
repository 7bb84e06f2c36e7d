// Slice stacking: order along the normal, spacing, irregular gaps, missing
// slices, gantry tilt and refusals, on positions worked out by hand.
#include "dicom/slice_stack.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace arbor::dicom {
namespace {

constexpr std::array<double, 6> kAxial = {1, 0, 0, 0, 1, 0};
constexpr std::array<double, 2> kPixels = {0.5, 0.5};

std::vector<Vec3> at_z(const std::vector<double> &z)
{
    std::vector<Vec3> p;
    for (double v : z)
        p.push_back({-100, -120, v});
    return p;
}

TEST(SliceStack, OrdersByPositionAlongTheNormalNotByInputOrder)
{
    const auto stack = plan_slice_stack(at_z({4, 0, 8, 2, 6}), kAxial, kPixels, 1, {});
    ASSERT_EQ(stack.slices.size(), 5u);
    const std::size_t expected[] = {1, 3, 0, 4, 2};
    for (std::size_t k = 0; k < 5; ++k) {
        EXPECT_EQ(stack.slices[k].a, expected[k]);
        EXPECT_EQ(stack.slices[k].t, 0.0);
    }
    EXPECT_DOUBLE_EQ(stack.spacing, 2.0);
    EXPECT_EQ(stack.origin, (Vec3{-100, -120, 0}));
    EXPECT_EQ(stack.normal, (Vec3{0, 0, 1}));
    EXPECT_TRUE(stack.notes.empty());
    EXPECT_TRUE(stack.frame_offsets.empty());
}

TEST(SliceStack, NormalFollowsTheOrientationForCoronalAndObliqueSlices)
{
    // Coronal: rows along +x, columns along -z; normal = x cross -z = +y.
    const std::array<double, 6> coronal = {1, 0, 0, 0, 0, -1};
    std::vector<Vec3> p = {{0, 3, 0}, {0, 1, 0}, {0, 2, 0}};
    auto stack = plan_slice_stack(p, coronal, kPixels, 1, {});
    EXPECT_EQ(stack.normal, (Vec3{0, 1, 0}));
    EXPECT_EQ(stack.slices[0].a, 1u);
    EXPECT_DOUBLE_EQ(stack.spacing, 1.0);

    // Oblique, 30 degrees about x: positions step along the normal.
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    const std::array<double, 6> oblique = {1, 0, 0, 0, c, s};
    const Vec3 n = slice_normal(oblique);
    EXPECT_NEAR(n[1], -s, 1e-12);
    EXPECT_NEAR(n[2], c, 1e-12);
    p.clear();
    for (int k : {2, 0, 1})
        p.push_back({0, 1.5 * k * n[1], 1.5 * k * n[2]});
    stack = plan_slice_stack(p, oblique, kPixels, 1, {});
    EXPECT_NEAR(stack.spacing, 1.5, 1e-12);
    EXPECT_EQ(stack.slices[0].a, 1u);
    EXPECT_TRUE(stack.frame_offsets.empty());
}

TEST(SliceStack, IrregularGapsAreResampledAndTheWeightsAreRight)
{
    // The shape of the shared head CT: gaps of 1.5 mm with one of 1.0 mm.
    std::vector<double> z;
    for (int k = 0; k < 5; ++k)
        z.push_back(1.5 * k); // 0 .. 6
    for (int k = 0; k < 4; ++k)
        z.push_back(7.0 + 1.5 * k); // 7 .. 11.5
    const auto stack = plan_slice_stack(at_z(z), kAxial, kPixels, 1, {});
    // extent 11.5, typical gap 1.5: round(11.5 / 1.5) + 1 = 9 slices, 11.5 / 8 apart.
    ASSERT_EQ(stack.slices.size(), 9u);
    EXPECT_DOUBLE_EQ(stack.spacing, 11.5 / 8);
    ASSERT_EQ(stack.notes.size(), 1u);
    EXPECT_NE(stack.notes[0].find("irregular"), std::string::npos);
    EXPECT_NE(stack.notes[0].find("7 gaps of 1.5 mm, 1 of 1 mm"), std::string::npos) << stack.notes[0];
    for (std::size_t k = 0; k < 9; ++k) {
        const double zk = k * stack.spacing;
        const SliceSource &s = stack.slices[k];
        const double interpolated = (1 - s.t) * z[s.a] + s.t * z[s.b];
        EXPECT_NEAR(interpolated, zk, 1e-9) << k;
        EXPECT_LE(z[s.a], zk + 1e-9);
        EXPECT_GE(z[s.b], zk - 1e-9);
    }
    EXPECT_EQ(stack.slices.front().t, 0.0);
    EXPECT_EQ(stack.slices.back().a, 8u);

    StackPolicy refuse;
    refuse.resample_irregular = false;
    try {
        plan_slice_stack(at_z(z), kAxial, kPixels, 1, refuse);
        FAIL() << "irregular gaps were not refused";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("irregular-slices"), std::string::npos) << e.what();
    }
}

TEST(SliceStack, SmallPositionJitterIsNotIrregular)
{
    std::vector<double> z;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.004, 0.004);
    for (int k = 0; k < 40; ++k)
        z.push_back(2.5 * k + jitter(rng));
    const auto stack = plan_slice_stack(at_z(z), kAxial, kPixels, 1, {});
    EXPECT_EQ(stack.slices.size(), 40u);
    EXPECT_TRUE(stack.notes.empty());
}

TEST(SliceStack, MissingSlicesAreRefusedByDefaultAndFilledWhenAsked)
{
    std::vector<double> z = {0, 2, 4, 10, 12}; // 6 and 8 are missing
    try {
        plan_slice_stack(at_z(z), kAxial, kPixels, 1, {});
        FAIL() << "missing slices were not refused";
    } catch (const std::runtime_error &e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("about 2 slice(s) missing"), std::string::npos) << m;
        EXPECT_NE(m.find("between positions 4 mm and 10 mm"), std::string::npos) << m;
        EXPECT_NE(m.find("missing-slices = interpolate"), std::string::npos) << m;
    }
    StackPolicy fill;
    fill.fill_missing = true;
    const auto stack = plan_slice_stack(at_z(z), kAxial, kPixels, 1, fill);
    ASSERT_EQ(stack.slices.size(), 7u);
    EXPECT_DOUBLE_EQ(stack.spacing, 2.0);
    // Slice 3 (z = 6) is a third of the way from z = 4 to z = 10.
    EXPECT_EQ(stack.slices[3].a, 2u);
    EXPECT_EQ(stack.slices[3].b, 3u);
    EXPECT_NEAR(stack.slices[3].t, 1.0 / 3, 1e-12);
    EXPECT_EQ(stack.slices[5].a, 3u); // z = 10 is measured
    EXPECT_EQ(stack.slices[5].t, 0.0);
}

TEST(SliceStack, TwoImagesAtOnePositionAreRefused)
{
    try {
        plan_slice_stack(at_z({0, 1, 1, 2, 3, 3}), kAxial, kPixels, 1, {});
        FAIL() << "duplicate positions were not refused";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("2 slice position(s) hold more than one image"), std::string::npos)
            << e.what();
    }
}

TEST(SliceStack, GantryTiltIsMeasuredAndEachFrameGetsItsOffset)
{
    // 20 degrees of tilt: each 2 mm step along z slides 2 tan(20) mm along -y
    // (the column direction of an axial image is +y).
    const double slide = 2 * std::tan(20 * M_PI / 180);
    std::vector<Vec3> p;
    for (int k : {3, 1, 0, 2})
        p.push_back({-100, -120 - slide * k, 2.0 * k});
    const auto stack = plan_slice_stack(p, kAxial, kPixels, 1, {});
    ASSERT_EQ(stack.frame_offsets.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(stack.frame_offsets[i][0], 0.0, 1e-12);
        EXPECT_NEAR(stack.frame_offsets[i][1], p[i][1] + 120, 1e-12);
    }
    EXPECT_DOUBLE_EQ(stack.spacing, 2.0);
    ASSERT_EQ(stack.notes.size(), 1u);
    EXPECT_NE(stack.notes[0].find("gantry tilt of about 20 degrees"), std::string::npos) << stack.notes[0];

    StackPolicy refuse;
    refuse.correct_tilt = false;
    EXPECT_THROW(plan_slice_stack(p, kAxial, kPixels, 1, refuse), std::runtime_error);
}

TEST(SliceStack, SingleFramesAndBadOrientations)
{
    const auto one = plan_slice_stack(at_z({5}), kAxial, kPixels, 3.0, {});
    EXPECT_EQ(one.slices.size(), 1u);
    EXPECT_EQ(one.spacing, 3.0);
    EXPECT_THROW(plan_slice_stack(at_z({0, 1}), {1, 0, 0, 1, 0, 0}, kPixels, 1, {}), std::runtime_error);
    EXPECT_THROW(plan_slice_stack(at_z({0, 1}), {2, 0, 0, 0, 1, 0}, kPixels, 1, {}), std::runtime_error);
    EXPECT_THROW(plan_slice_stack({}, kAxial, kPixels, 1, {}), std::runtime_error);
}

} // namespace
} // namespace arbor::dicom
