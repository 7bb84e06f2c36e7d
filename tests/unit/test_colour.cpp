// Colour spaces (HSV, sRGB, CIELAB), vividness and the lightness/vividness
// search of the transfer-function generators, and the harmonic hue
// templates of Cohen-Or et al. 2006.
#include "colour_space.hpp"
#include "harmonic_template.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace arbor::tf {
namespace {

void expect_rgb(const Rgb &c, double r, double g, double b, double tolerance = 1e-12)
{
    EXPECT_NEAR(c.r, r, tolerance);
    EXPECT_NEAR(c.g, g, tolerance);
    EXPECT_NEAR(c.b, b, tolerance);
}

TEST(ColourSpace, SrgbLabRoundTripsOnAGrid)
{
    double worst = 0.0;
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j <= 10; ++j)
            for (int k = 0; k <= 10; ++k) {
                const Rgb c{i / 10.0, j / 10.0, k / 10.0};
                const Rgb back = lab_to_srgb(srgb_to_lab(c));
                worst = std::max({worst, std::abs(back.r - c.r), std::abs(back.g - c.g), std::abs(back.b - c.b)});
            }
    EXPECT_LT(worst, 1e-9);
}

TEST(ColourSpace, TransferCurvesInvertEachOther)
{
    for (int i = 0; i <= 100; ++i) {
        const double c = i / 100.0;
        EXPECT_NEAR(linear_to_srgb(srgb_to_linear(c)), c, 1e-12);
        EXPECT_NEAR(srgb_to_linear(linear_to_srgb(c)), c, 1e-12);
    }
    EXPECT_NEAR(srgb_to_linear(0.5), 0.214041, 1e-6);
    EXPECT_DOUBLE_EQ(srgb_to_linear(1.0), 1.0);
}

TEST(ColourSpace, WhiteAndBlackAreAchromatic)
{
    // The matrix's rows are normalised onto the reference white, so white
    // and every grey are achromatic to rounding.
    const Lab white = srgb_to_lab({1.0, 1.0, 1.0});
    EXPECT_NEAR(white.L, 100.0, 1e-9);
    EXPECT_NEAR(white.a, 0.0, 1e-9);
    EXPECT_NEAR(white.b, 0.0, 1e-9);
    for (double g : {0.01, 0.2, 0.5, 0.9}) {
        const Lab grey = srgb_to_lab({g, g, g});
        EXPECT_NEAR(chroma(grey), 0.0, 1e-9) << g;
    }

    const Lab black = srgb_to_lab({0.0, 0.0, 0.0});
    EXPECT_NEAR(black.L, 0.0, 1e-12);
    EXPECT_NEAR(black.a, 0.0, 1e-12);
    EXPECT_NEAR(black.b, 0.0, 1e-12);
}

TEST(ColourSpace, PureRedHasItsPublishedLab)
{
    const Lab red = srgb_to_lab({1.0, 0.0, 0.0});
    EXPECT_NEAR(red.L, 53.24, 0.05);
    EXPECT_NEAR(red.a, 80.09, 0.05);
    EXPECT_NEAR(red.b, 67.20, 0.05);
    EXPECT_NEAR(chroma(red), std::hypot(red.a, red.b), 1e-12);
}

TEST(ColourSpace, OutOfGamutLabIsNotClamped)
{
    // Far more chroma than any sRGB colour at this lightness.
    const Rgb c = lab_to_srgb({50.0, 0.0, -150.0});
    EXPECT_TRUE(c.r < 0.0 || c.g < 0.0 || c.b > 1.0);
}

TEST(ColourSpace, HsvKnownValues)
{
    expect_rgb(hsv_to_rgb(0.0, 1.0, 1.0), 1.0, 0.0, 0.0);
    expect_rgb(hsv_to_rgb(60.0, 1.0, 1.0), 1.0, 1.0, 0.0);
    expect_rgb(hsv_to_rgb(120.0, 1.0, 1.0), 0.0, 1.0, 0.0);
    expect_rgb(hsv_to_rgb(240.0, 1.0, 1.0), 0.0, 0.0, 1.0);
    expect_rgb(hsv_to_rgb(120.0, 0.5, 0.8), 0.4, 0.8, 0.4);
    expect_rgb(hsv_to_rgb(200.0, 0.0, 0.3), 0.3, 0.3, 0.3);
    // The hue wraps.
    expect_rgb(hsv_to_rgb(360.0, 1.0, 1.0), 1.0, 0.0, 0.0);
    expect_rgb(hsv_to_rgb(-120.0, 1.0, 1.0), 0.0, 0.0, 1.0);
    expect_rgb(hsv_to_rgb(480.0, 1.0, 1.0), 0.0, 1.0, 0.0);
}

TEST(ColourSpace, VividnessIsOneForPureHuesAndZeroForGreys)
{
    for (int h = 0; h < 360; h += 5) {
        EXPECT_NEAR(vividness(h, 1.0, 1.0), 1.0, 1e-12) << "hue " << h;
        for (double v : {0.0, 0.3, 1.0})
            EXPECT_NEAR(vividness(h, 0.0, v), 0.0, 1e-9) << "hue " << h << " v " << v;
    }
}

TEST(ColourFor, MeetsReachableTargetsAcrossTheWheel)
{
    int combinations = 0, exact = 0;
    for (int h = 0; h < 360; h += 15)
        for (double L : {40.0, 55.0, 70.0})
            for (double vivid : {0.2, 0.5, 0.8}) {
                ++combinations;
                const LightVivid c = colour_for(h, L, vivid);
                SCOPED_TRACE("hue " + std::to_string(h) + " L " + std::to_string(L) + " vividness " +
                             std::to_string(vivid));
                ASSERT_GE(c.s, 0.0);
                ASSERT_LE(c.s, 1.0);
                ASSERT_GE(c.v, 0.0);
                ASSERT_LE(c.v, 1.0);
                // The reported figures are those of the returned colour.
                const Rgb recomputed = hsv_to_rgb(h, c.s, c.v);
                expect_rgb(c.rgb, recomputed.r, recomputed.g, recomputed.b);
                EXPECT_NEAR(srgb_to_lab(c.rgb).L, c.achieved_L, 1e-9);
                EXPECT_NEAR(vividness(h, c.s, c.v), c.achieved_vividness, 1e-9);
                if (!c.exact)
                    continue;
                ++exact;
                EXPECT_LT(std::abs(c.achieved_L - L), 0.1);
                EXPECT_LT(std::abs(c.achieved_vividness - vivid), 0.005);
            }
    // Measured: 163 of 216 (75.5%).  The misses are physical: dark yellows
    // and greens cannot be vivid, light blues and purples neither.
    EXPECT_GE(static_cast<double>(exact) / combinations, 0.75) << exact << " of " << combinations;
}

TEST(ColourFor, TooVividForTheLightnessKeepsTheLightness)
{
    // Yellow at L* 40 is an olive whose vividness stays near 0.5.
    const LightVivid c = colour_for(60.0, 40.0, 0.8);
    EXPECT_FALSE(c.exact);
    EXPECT_NEAR(c.achieved_L, 40.0, 1e-6);
    EXPECT_DOUBLE_EQ(c.s, 1.0);
    EXPECT_LT(c.achieved_vividness, 0.8);
    EXPECT_GT(c.achieved_vividness, 0.4);
}

TEST(ColourFor, TooLightForTheVividnessKeepsTheVividness)
{
    // Pure blue has L* 32; a vivid blue cannot be light.
    const LightVivid c = colour_for(240.0, 70.0, 0.8);
    EXPECT_FALSE(c.exact);
    EXPECT_NEAR(c.achieved_vividness, 0.8, 1e-6);
    EXPECT_DOUBLE_EQ(c.v, 1.0);
    EXPECT_LT(c.achieved_L, 70.0);
}

TEST(ColourFor, EdgeTargets)
{
    const LightVivid grey = colour_for(200.0, 50.0, 0.0);
    EXPECT_TRUE(grey.exact);
    EXPECT_NEAR(grey.s, 0.0, 1e-9);
    EXPECT_NEAR(grey.achieved_L, 50.0, 1e-6);

    const LightVivid pure = colour_for(0.0, srgb_to_lab({1.0, 0.0, 0.0}).L, 1.0);
    EXPECT_TRUE(pure.exact);
    expect_rgb(pure.rgb, 1.0, 0.0, 0.0, 1e-6);

    const LightVivid black = colour_for(120.0, 0.0, 0.5);
    EXPECT_FALSE(black.exact);
    EXPECT_NEAR(black.achieved_L, 0.0, 1e-9);

    // Out-of-range targets are clamped and so never exact.
    const LightVivid beyond = colour_for(120.0, 120.0, 0.0);
    EXPECT_FALSE(beyond.exact);
    EXPECT_NEAR(beyond.achieved_L, 100.0, 1e-6);

    EXPECT_THROW(colour_for(std::numeric_limits<double>::quiet_NaN(), 50.0, 0.5), std::invalid_argument);
    EXPECT_THROW(colour_for(0.0, std::numeric_limits<double>::infinity(), 0.5), std::invalid_argument);
}

TEST(HarmonicTemplate, ParsesEveryName)
{
    const struct {
        const char *spec, *name;
        std::size_t sectors;
    } cases[] = {{"i", "i", 1}, {"V", "V", 1}, {"L", "L", 2}, {"I", "I", 2}, {"T", "T", 1},
                 {"Y", "Y", 2}, {"X", "X", 2}, {"N", "N", 1}, {"full", "N", 1}};
    for (const auto &c : cases) {
        const HarmonicTemplate t = HarmonicTemplate::parse(c.spec);
        EXPECT_EQ(t.name(), c.name) << c.spec;
        EXPECT_EQ(t.sectors().size(), c.sectors) << c.spec;
        EXPECT_DOUBLE_EQ(t.rotation(), 0.0) << c.spec;
    }
    const HarmonicTemplate l = HarmonicTemplate::parse("L");
    EXPECT_DOUBLE_EQ(l.sectors()[0].width, 18.0);
    EXPECT_DOUBLE_EQ(l.sectors()[1].centre, 90.0);
    EXPECT_DOUBLE_EQ(l.sectors()[1].width, 79.2);
}

TEST(HarmonicTemplate, AppliesTheRotation)
{
    const HarmonicTemplate x = HarmonicTemplate::parse("X:30");
    EXPECT_EQ(x.name(), "X");
    EXPECT_DOUBLE_EQ(x.rotation(), 30.0);
    ASSERT_EQ(x.sectors().size(), 2u);
    EXPECT_DOUBLE_EQ(x.sectors()[0].centre, 30.0);
    EXPECT_DOUBLE_EQ(x.sectors()[1].centre, 210.0);
    EXPECT_DOUBLE_EQ(x.sectors()[0].width, 93.6);

    const HarmonicTemplate i = HarmonicTemplate::parse("I:-90");
    EXPECT_DOUBLE_EQ(i.rotation(), 270.0);
    EXPECT_DOUBLE_EQ(i.sectors()[0].centre, 270.0);
    EXPECT_DOUBLE_EQ(i.sectors()[1].centre, 90.0);

    EXPECT_DOUBLE_EQ(HarmonicTemplate::parse("V:+12.5").rotation(), 12.5);
}

TEST(HarmonicTemplate, ContainsHandlesWrapAround)
{
    const HarmonicTemplate v = HarmonicTemplate::parse("V"); // 313.2 .. 46.8
    EXPECT_TRUE(v.contains(0.0));
    EXPECT_TRUE(v.contains(350.0));
    EXPECT_TRUE(v.contains(-10.0));
    EXPECT_TRUE(v.contains(46.8));
    EXPECT_FALSE(v.contains(50.0));
    EXPECT_FALSE(v.contains(180.0));

    const HarmonicTemplate full = HarmonicTemplate::parse("full:45");
    for (int h = 0; h < 360; h += 7)
        EXPECT_TRUE(full.contains(h));
}

TEST(HarmonicTemplate, SpreadHuesLieInTheTemplate)
{
    for (const char *spec : {"i", "V", "L", "I", "T", "Y", "X", "N", "X:30", "L:300", "Y:-77.5", "i:359"}) {
        const HarmonicTemplate t = HarmonicTemplate::parse(spec);
        for (std::size_t n : {1u, 5u, 17u}) {
            const std::vector<double> hues = t.spread(n);
            ASSERT_EQ(hues.size(), n);
            for (double h : hues) {
                EXPECT_GE(h, 0.0) << spec;
                EXPECT_LT(h, 360.0) << spec;
                EXPECT_TRUE(t.contains(h)) << spec << " n " << n << " hue " << h;
            }
        }
    }
    EXPECT_TRUE(HarmonicTemplate::parse("X").spread(0).empty());
}

TEST(HarmonicTemplate, HueAtWalksTheArcsInOrder)
{
    const HarmonicTemplate x = HarmonicTemplate::parse("X:30");
    EXPECT_NEAR(x.hue_at(0.0), 30.0 - 46.8 + 360.0, 1e-9); // the first sector's start, wrapped
    EXPECT_NEAR(x.hue_at(0.25), 30.0, 1e-9);
    EXPECT_NEAR(x.hue_at(0.5), 210.0 - 46.8, 1e-9);
    EXPECT_NEAR(x.hue_at(0.75), 210.0, 1e-9);

    const HarmonicTemplate i = HarmonicTemplate::parse("i");
    EXPECT_NEAR(i.hue_at(0.0), 351.0, 1e-9);
    EXPECT_NEAR(i.hue_at(0.5), 0.0, 1e-9);
    EXPECT_NEAR(i.hue_at(1.25), i.hue_at(0.25), 1e-9); // t wraps
}

TEST(HarmonicTemplate, RejectsBadSpecsNamingTheValidOnes)
{
    for (const char *spec : {"", "Q", "x", "X:", "X:abc", "X:30deg", "X:inf", "X:nan", "X:+-30", "fullish"}) {
        try {
            HarmonicTemplate::parse(spec);
            ADD_FAILURE() << "accepted \"" << spec << "\"";
        } catch (const std::invalid_argument &error) {
            const std::string message = error.what();
            EXPECT_NE(message.find("i, V, L, I, T, Y, X, N"), std::string::npos) << message;
            EXPECT_NE(message.find("full"), std::string::npos) << message;
        }
    }
}

} // namespace
} // namespace arbor::tf
