// The pieces the default image stands on, on volumes made to know the
// answer: the background level of a histogram, the thickness and
// compactness of labelled structures, the extrema count on a known field,
// the denoising study's plateau, CT tissue names, framing, and the
// balancing of visibility against a renderer whose answer is known.
#include "core/background_level.hpp"
#include "core/ct_tissue.hpp"
#include "core/volume.hpp"
#include "pipeline/auto_denoise.hpp"
#include "pipeline/framing.hpp"
#include "pipeline/visibility_balance.hpp"
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

TEST(LabelShapes, FacesBetweenTheSlabsOfDifferentCoresCount)
{
    // Two blocks of 5 x 3 x 16 voxels stacked in z: the slices are shared
    // out between cores (two on this machine), and the one face plane
    // between the labels lies where the halves meet.  Counted by hand:
    // 240 voxels each, 15 faces between them (the grid's border does not
    // count), thickness 1.5 x 2 x volume / area.
    constexpr int64_t nx = 5, ny = 3, nz = 32;
    std::vector<uint32_t> labels(static_cast<std::size_t>(nx * ny * nz), 0);
    for (std::size_t v = static_cast<std::size_t>(nx * ny * nz / 2); v < labels.size(); ++v)
        labels[v] = 1;
    const std::array<double, 3> spacing{0.5, 2.0, 1.5};
    const auto s = topology::label_shapes(labels, {nx, ny, nz}, spacing, 3);
    const double volume = 240 * 0.5 * 2.0 * 1.5, area = 15 * 0.5 * 2.0;
    for (int l = 0; l < 2; ++l) {
        EXPECT_NEAR(s[l].thickness_mm, 1.5 * 2 * volume / area, 1e-9) << "label " << l;
        EXPECT_NEAR(s[l].compactness, s[l].thickness_mm / std::cbrt(volume), 1e-9) << "label " << l;
    }
    EXPECT_EQ(s[2].thickness_mm, 0.0); // no voxels
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
    EXPECT_FALSE(pipeline::find_plateau({1000, 100, 10}));    // ... which is no plateau
    // A weak start that changes little is not the plateau: it comes after
    // the steepest step.
    EXPECT_EQ(pipeline::find_plateau({1000, 990, 980, 100, 98}), 3u);
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

// A renderer one can work out by hand: every ray crosses the body (the
// root, one layer), then, on its share of the pixels, the layers of the
// structures in front-to-back order; each layer's opacity is its transfer
// function's densest alpha.  Structure 1 is a big slab over 60 % of the
// pixels, 2 a small solid inside it (4 %, behind 1), 3 a thin sheet in front
// of everything (30 %), 4 a small solid on 2 % of the pixels alone.
struct LayeredScene {
    struct Layer {
        uint32_t branch;
        double x0, x1; // the pixel columns it covers, as fractions of the width
    };
    std::vector<Layer> layers{{3, 0.0, 0.3}, {1, 0.2, 0.8}, {2, 0.4, 0.44}, {4, 0.9, 0.92}};
    int renders = 0;

    RenderedImage operator()(const TransferFunctions &tf, uint32_t size)
    {
        ++renders;
        const auto alpha = [&](uint32_t b) {
            float a = 0;
            for (uint32_t e = 0; e < tf.lut_size(); ++e)
                a = std::max(a, tf.lut(b)[4 * e + 3]);
            return static_cast<double>(a);
        };
        RenderedImage im;
        im.width = im.height = size;
        im.rgba.assign(std::size_t{size} * size * 4, 0.0f);
        im.label_visibility.assign(tf.branch_count(), 0.0);
        for (uint32_t x = 0; x < size; ++x) {
            const double at = (x + 0.5) / size;
            double t = 1.0;
            const auto cross = [&](uint32_t b) {
                im.label_visibility[b] += size * t * alpha(b); // a column of `size` rays
                t *= 1 - alpha(b);
            };
            cross(0);
            for (const Layer &l : layers)
                if (at >= l.x0 && at < l.x1)
                    cross(l.branch);
            for (uint32_t y = 0; y < size; ++y)
                im.rgba[(std::size_t{y} * size + x) * 4 + 3] = static_cast<float>(1 - t);
        }
        return im;
    }
};

// Transfer functions for LayeredScene's five branches (tf of 5 x 2 entries)
// as a residue flow might leave them: the body dense, the inner solid and
// the speck faint.
void assign_layered(TransferFunctions &tf)
{
    const std::vector<float> densest = {0.5f, 0.3f, 0.02f, 0.4f, 0.01f};
    for (uint32_t b = 0; b < 5; ++b) {
        const float rgba[8] = {1, 1, 1, 0, 1, 1, 1, densest[b]};
        tf.assign(b, {0.0, 1.0}, rgba);
    }
}

// LayeredScene's branch tree: the solid inside the slab, the rest in the body.
pipeline::BranchLayout layered_layout()
{
    pipeline::BranchLayout layout;
    layout.parent = {-1, 0, 1, 0, 0};
    layout.voxels = {1e6, 6e4, 4e3, 3e4, 1e3};
    layout.sheet = {false, false, false, true, false};
    return layout;
}

TEST(VisibilityBalance, EveryStructureGetsItsShareAndTheBodyItsBounds)
{
    TransferFunctions tf(5, 2, 1.0);
    assign_layered(tf);
    const pipeline::BranchLayout layout = layered_layout();
    LayeredScene scene;
    Geometry g;
    g.dims = {32, 32, 32};
    const pipeline::BalanceTargets targets;
    const auto r = pipeline::balance_visibility(
        tf, layout, g, [&](const TransferFunctions &f, const arbor_camera &, uint32_t size) { return scene(f, size); },
        targets);
    ASSERT_EQ(r.shares_after.size(), 5u);
    EXPECT_LT(r.shares_before[2], 0.01); // hidden behind the slab and faint
    EXPECT_GT(r.shares_before[0], targets.root_cap); // the body takes the picture
    double sum = 0;
    for (const double s : r.shares_after)
        sum += s;
    EXPECT_NEAR(sum, 1.0, 1e-9);
    // Every structure at its floor (within the iterations' tolerance), the
    // body within its bounds, the sheet under its cap.
    for (uint32_t b = 1; b < 5; ++b)
        EXPECT_GE(r.shares_after[b], 0.8 * targets.floor) << "structure " << b;
    EXPECT_GE(r.shares_after[0], 0.8 * targets.root_floor);
    EXPECT_LE(r.shares_after[0], 1.1 * targets.root_cap);
    EXPECT_LE(r.shares_after[3], 1.1 * targets.sheet_cap);
    // What was already in bounds is not pushed out of them: the faint inner
    // solid was made denser, not the slab in front of it.
    EXPECT_GT(r.scale[2], r.scale[1]);
    for (const double s : r.scale) {
        EXPECT_TRUE(std::isfinite(s));
        EXPECT_GT(s, 0);
    }
    EXPECT_GE(scene.renders, 3); // three views per measurement
}

// A structure that is context (outside the body, or cut by the field of
// view) is held at its cap however much of the picture it would take, and
// gets no floor: the sheet in front (30 % of the pixels) as a headrest.
TEST(VisibilityBalance, ContextStaysFaintAndTheRestShareThePicture)
{
    TransferFunctions tf(5, 2, 1.0);
    assign_layered(tf);
    pipeline::BranchLayout layout = layered_layout();
    layout.context = {false, false, false, true, false};
    LayeredScene scene;
    Geometry g;
    g.dims = {32, 32, 32};
    const pipeline::BalanceTargets targets;
    const auto r = pipeline::balance_visibility(
        tf, layout, g, [&](const TransferFunctions &f, const arbor_camera &, uint32_t size) { return scene(f, size); },
        targets);
    EXPECT_GT(r.shares_before[3], 0.05);
    EXPECT_LE(r.shares_after[3], 1.2 * targets.context_cap);
    EXPECT_LT(r.scale[3], 1.0);
    for (const uint32_t b : {1u, 2u, 4u})
        EXPECT_GE(r.shares_after[b], 0.8 * targets.floor) << "structure " << b;
    // Unseen context is not made denser until it shows.
    layout.context = {false, false, false, false, true};
    assign_layered(tf);
    const float nothing[8] = {1, 1, 1, 0, 1, 1, 1, 0};
    tf.assign(4, {0.0, 1.0}, nothing);
    LayeredScene again;
    const auto unseen = pipeline::balance_visibility(
        tf, layout, g, [&](const TransferFunctions &f, const arbor_camera &, uint32_t size) { return again(f, size); },
        targets);
    EXPECT_LE(unseen.scale[4], 1.0);
}

// The layered scene balanced with `focus` selected (-1: none).
pipeline::BalanceResult balance_layered(int32_t focus)
{
    TransferFunctions tf(5, 2, 1.0);
    assign_layered(tf);
    Geometry g;
    g.dims = {32, 32, 32};
    LayeredScene scene;
    pipeline::BalanceTargets targets;
    targets.focus = focus;
    return pipeline::balance_visibility(
        tf, layered_layout(), g,
        [&](const TransferFunctions &f, const arbor_camera &, uint32_t size) { return scene(f, size); }, targets);
}

TEST(VisibilityBalance, ASelectedStructureIsBroughtForward)
{
    // The same scene; the small solid inside the slab (4 % of the pixels) is
    // selected.  Without the selection it ends at its floor, below the
    // slab, the body and the sheet; selected, it is made as dense as it can
    // be and the slab in front of it is peeled, the body within its bounds.
    const auto rank = [](const std::vector<double> &shares, uint32_t b) {
        return std::count_if(shares.begin(), shares.end(), [&](double s) { return s > shares[b]; });
    };
    const auto plain = balance_layered(-1), focused = balance_layered(2);
    EXPECT_GE(rank(plain.shares_after, 2), 3); // fourth or later
    // At its densest already, it cannot reach the focus floor on 4 % of the
    // pixels behind a body that covers all of them; it comes forward.
    EXPECT_GE(focused.shares_after[2], 5 * plain.shares_after[2]);
    EXPECT_LE(rank(focused.shares_after, 2), 2); // among the three most visible
    const pipeline::BalanceTargets targets;
    EXPECT_LT(focused.scale[1], plain.scale[1]); // the slab in front was thinned
    EXPECT_GE(focused.shares_after[0], 0.8 * targets.root_floor);
    for (uint32_t b = 1; b < 5; ++b)
        EXPECT_GE(focused.shares_after[b], 0.8 * targets.floor) << "structure " << b; // context kept
}

TEST(VisibilityBalance, ASelectionKeepsItsContextReadable)
{
    // The same scene and selection.  The sheet and the small structure at
    // the side are context: they hide nothing of the selected solid, so
    // thinning them would only darken the picture around it.  They may make
    // room, but keep at least half the optical depth they have without the
    // selection, while the slab in front (the solid's parent) is peeled
    // further than that.
    const auto plain = balance_layered(-1), focused = balance_layered(2);
    for (const uint32_t b : {3u, 4u})
        EXPECT_GE(focused.scale[b], 0.5 * plain.scale[b] * (1 - 1e-12)) << "structure " << b;
    EXPECT_LT(focused.scale[1], 0.5 * plain.scale[1]); // the slab in front
    EXPECT_EQ(focused.shares_before, plain.shares_before); // both start from the generator's functions
}

TEST(VisibilityBalance, ARendererThatMeasuresNothingIsRefused)
{
    TransferFunctions tf(2, 2, 1.0);
    const float rgba[8] = {1, 1, 1, 0, 1, 1, 1, 0.5f};
    tf.assign(0, {0.0, 1.0}, rgba);
    tf.assign(1, {0.0, 1.0}, rgba);
    pipeline::BranchLayout layout{{-1, 0}, {10, 10}, {false, false}, {}};
    Geometry g;
    g.dims = {8, 8, 8};
    EXPECT_THROW(pipeline::balance_visibility(tf, layout, g,
                                              [](const TransferFunctions &, const arbor_camera &, uint32_t size) {
                                                  RenderedImage im;
                                                  im.width = im.height = size;
                                                  im.rgba.assign(std::size_t{size} * size * 4, 0.0f);
                                                  return im;
                                              }),
                 std::invalid_argument);
}

} // namespace
} // namespace arbor
