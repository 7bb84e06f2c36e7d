// What a sample of the CPU ray caster takes from its position rather than
// from its nearest voxel (issue "Smooth structures"), against answers known
// in closed form:
// - labels resolved by the sample's value (topology-controlled volume
//   rendering): on a ramp, the boundaries between a basin, the root, a peak
//   and a peak nested in it lie at their saddle values, not halfway between
//   voxels, whatever the labels' kinds and depths;
// - gradients at the sample: an opaque ball's shading follows its true
//   normals closer than with each voxel's normal;
// - the faces of the field of view: a ray entering and leaving through
//   them integrates exactly the chord inside, whatever its jitter, so a cut
//   face does not speckle;
// - local ambient occlusion: the floor of a trench darkens, an open floor
//   does not.
#include "plugin_fixture.hpp"

#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor {
namespace {

constexpr uint32_t kLut = 256;

struct Grid {
    Volume volume;
    std::vector<uint32_t> labels;
    std::vector<int32_t> parent;
    std::vector<double> saddle;
};

Volume allocate(int64_t nx, int64_t ny, int64_t nz)
{
    Geometry g;
    g.dims = {nx, ny, nz};
    g.spacing = {1, 1, 1};
    g.origin = {0, 0, 0};
    return Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
}

// White, transparent below `threshold` of [0, hi] and opaque from it.
void opaque_from(TransferFunctions &tf, double threshold, double hi)
{
    std::vector<float> lut(kLut * 4, 1.0f);
    for (uint32_t i = 0; i < kLut; ++i)
        lut[4 * i + 3] = hi * i / (kLut - 1) >= threshold ? 1.0f : 0.0f;
    tf.assign(0, {0.0, hi}, lut.data());
}

// Constant colour `rgb` at opacity `alpha` (per mm) over [lo, hi].
void constant(TransferFunctions &tf, uint32_t b, std::array<float, 3> rgb, float alpha, double lo = 0, double hi = 100)
{
    std::vector<float> lut(kLut * 4);
    for (uint32_t i = 0; i < kLut; ++i) {
        for (int c = 0; c < 3; ++c)
            lut[4 * i + c] = rgb[c];
        lut[4 * i + 3] = alpha;
    }
    tf.assign(b, {lo, hi}, lut.data());
}

struct Scene {
    PluginInstance renderer = test::built_plugins().create("org.arbor.renderer.cpu-raycast");
    arbor_camera camera{};
    uint64_t revision = 0;

    Scene()
    {
        set("shading", "false");
        set("jitter", "false");
        set("boundary-emphasis", "0");
        set("termination", "1");
        camera.struct_size = sizeof camera;
        camera.projection = ARBOR_PROJECTION_ORTHOGRAPHIC;
    }
    void set(const std::string &param, const std::string &text)
    {
        renderer.set_param(param, parse_param_value(*renderer.find_param(param), text).value);
    }
    // Shaded by the headlight without highlights: ambient + diffuse * |n . l|.
    void light(const char *ambient, const char *diffuse)
    {
        set("shading", "true");
        set("specular", "0");
        set("ambient", ambient);
        set("diffuse", diffuse);
    }
    // Looking along +z at the centre of the grid's x-y extent, the image
    // spanning `half` mm above and below it.
    void look_along_z(const Volume &v, double half)
    {
        const auto &d = v.geometry().dims;
        const double cx = (d[0] - 1) / 2.0, cy = (d[1] - 1) / 2.0, cz = (d[2] - 1) / 2.0;
        camera.position[0] = cx, camera.position[1] = cy, camera.position[2] = -500;
        camera.focal_point[0] = cx, camera.focal_point[1] = cy, camera.focal_point[2] = cz;
        camera.view_up[0] = 0, camera.view_up[1] = 1, camera.view_up[2] = 0;
        camera.parallel_scale = half;
    }
    RenderedImage render(const Grid &g, const TransferFunctions &tf, uint32_t w, uint32_t h, bool hierarchy = true)
    {
        const arbor_volume view = g.volume.view();
        arbor_label_map map{};
        map.struct_size = sizeof map;
        map.label_count = tf.branch_count();
        for (int a = 0; a < 3; ++a)
            map.dims[a] = g.volume.geometry().dims[a];
        map.labels = g.labels.empty() ? nullptr : g.labels.data();
        if (hierarchy && !g.parent.empty()) {
            map.parent = g.parent.data();
            map.saddle_value = g.saddle.data();
        }
        arbor_render_request r{};
        r.struct_size = sizeof r;
        r.volume = &view;
        r.labels = g.labels.empty() ? nullptr : &map;
        r.transfer_functions = &tf.record();
        r.camera = &camera;
        r.volume_revision = ++revision;
        r.labels_revision = revision;
        return render_image(renderer, r, w, h);
    }
};

const float *pixel(const RenderedImage &im, uint32_t x, uint32_t y)
{
    return &im.rgba[(std::size_t{y} * im.width + x) * 4];
}

// A ramp f = i along x (32 x 4 x 4 voxels), labelled as a contour tree cut
// would label it: a basin (label 1, values up to its saddle 6.3), the root
// (0), a peak (2, from 12.7) and a peak nested in it (3, from 22.2).  Each
// voxel takes the label of its own value.
Grid ramp()
{
    Grid g{allocate(32, 4, 4), {}, {-1, 0, 0, 2}, {0.0, 6.3, 12.7, 22.2}};
    g.labels.resize(32 * 4 * 4);
    for (std::size_t v = 0; v < g.labels.size(); ++v) {
        const float f = static_cast<float>(v % 32);
        g.volume.as<float>()[v] = f;
        g.labels[v] = f <= 6.3f ? 1u : f >= 22.2f ? 3u : f >= 12.7f ? 2u : 0u;
    }
    return g;
}

// The label map's x at the centre of image column x: 8 columns a voxel.
double voxel_x(uint32_t column) { return -0.5 + (column + 0.5) / 8.0; }

TEST(SampleLabels, BoundariesLieAtTheSaddleValuesOfEveryKindAndDepth)
{
    const Grid g = ramp();
    TransferFunctions tf(4, kLut, 1.0);
    const std::array<std::array<float, 3>, 4> colour = {{{1, 1, 1}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}}};
    for (uint32_t b = 0; b < 4; ++b)
        constant(tf, b, colour[b], 0.9f, 0, 31);
    // f = x: the label a sample of value x takes.
    const auto expected = [](double x) { return x <= 6.3 ? 1 : x >= 22.2 ? 3 : x >= 12.7 ? 2 : 0; };
    for (const bool per_sample : {true, false}) {
        Scene s;
        s.set("sample-labels", per_sample ? "true" : "false");
        s.look_along_z(g.volume, 2.0); // 32 pixels of height: 4 voxels
        const RenderedImage im = s.render(g, tf, 256, 32);
        int wrong = 0, near_boundary_wrong = 0;
        for (uint32_t x = 4; x < 252; ++x) {
            const float *p = pixel(im, 255 - x, 16); // +x points to the image's left
            int seen = -1;
            for (int b = 0; b < 4; ++b)
                if (std::fabs(p[0] - colour[b][0] * p[3]) < 0.05f && std::fabs(p[1] - colour[b][1] * p[3]) < 0.05f &&
                    std::fabs(p[2] - colour[b][2] * p[3]) < 0.05f)
                    seen = b;
            const double at = voxel_x(x);
            if (seen != expected(at)) {
                ++wrong;
                // Within half a pixel of a boundary, either side is right.
                if (expected(at - 1.0 / 16) == expected(at + 1.0 / 16))
                    ++near_boundary_wrong;
            }
        }
        if (per_sample) {
            EXPECT_EQ(near_boundary_wrong, 0) << "columns whose label is not the one their value lies in";
        } else {
            // Nearest voxels put the boundaries halfway between voxels:
            // 6.5, 12.5 and 22.5 instead of 6.3, 12.7 and 22.2 (1 + 1 + 2
            // columns more than half a pixel off), which this test must be
            // able to see.
            EXPECT_GE(near_boundary_wrong, 3);
        }
    }
}

// Two structures whose voxels meet, a basin (up to 15.5) and a peak (from
// 15.8), have the root between them with no voxel of its own: samples of
// values in (15.5, 15.8) resolve to it.  Empty-space skipping must know
// that a block of the two can show the root, which alone is opaque here.
TEST(SampleLabels, ASharedAncestorWithoutVoxelsIsNotSkipped)
{
    Grid g{allocate(32, 4, 4), {}, {-1, 0, 0}, {0.0, 15.5, 15.8}};
    g.labels.resize(32 * 4 * 4);
    for (std::size_t v = 0; v < g.labels.size(); ++v) {
        g.volume.as<float>()[v] = static_cast<float>(v % 32);
        g.labels[v] = v % 32 <= 15 ? 1u : 2u;
    }
    TransferFunctions tf(3, kLut, 1.0);
    constant(tf, 0, {1, 0, 0}, 0.9f, 0, 31);
    constant(tf, 1, {0, 0, 1}, 0.0f, 0, 31);
    constant(tf, 2, {0, 1, 0}, 0.0f, 0, 31);
    Scene s;
    s.look_along_z(g.volume, 2.0);
    const RenderedImage im = s.render(g, tf, 256, 32);
    const auto at = [&](double x) { return pixel(im, 255 - static_cast<uint32_t>((x + 0.5) * 8), 16); };
    EXPECT_GT(at(15.65)[3], 0.5f) << "the root between them";
    EXPECT_GT(at(15.65)[0], 0.5f);
    EXPECT_LT(at(15.2)[3], 0.01f);
    EXPECT_LT(at(16.2)[3], 0.01f);
}

TEST(SampleLabels, WithoutTheLabelsTreeTheNearestVoxelDecides)
{
    const Grid g = ramp();
    TransferFunctions tf(4, kLut, 1.0);
    for (uint32_t b = 0; b < 4; ++b)
        constant(tf, b, {b == 2 ? 1.0f : 0.0f, 0, 0}, 0.9f, 0, 31);
    Scene s;
    s.look_along_z(g.volume, 2.0);
    const RenderedImage with = s.render(g, tf, 256, 32, true), without = s.render(g, tf, 256, 32, false);
    // Column of x = 12.6: value 12.6 is below the peak's saddle (12.7), its
    // nearest voxel (13) is in the peak.
    const uint32_t column = 255 - static_cast<uint32_t>((12.6 + 0.5) * 8);
    EXPECT_LT(pixel(with, column, 16)[0], 0.05f);
    EXPECT_GT(pixel(without, column, 16)[0], 0.5f);
}

// An opaque ball f = 40 - r of radius 12 mm (threshold 28), lit by the
// headlight, unshaded elsewhere: a pixel's brightness is ambient + diffuse *
// |n . l| + specular at the true normal n of the sphere where the ray meets
// it.  Per-sample gradients follow it closer than each voxel's normal.
TEST(SampleGradients, ShadingFollowsTheTrueNormalsOfABall)
{
    constexpr int64_t n = 40;
    Grid g{allocate(n, n, n), {}, {}, {}};
    const double c = (n - 1) / 2.0;
    for (int64_t k = 0; k < n; ++k)
        for (int64_t j = 0; j < n; ++j)
            for (int64_t i = 0; i < n; ++i)
                g.volume.as<float>()[i + n * (j + n * k)] =
                    static_cast<float>(40.0 - std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c)));
    TransferFunctions tf(1, kLut, 1.0);
    opaque_from(tf, 28.0, 40.0);
    double error[2] = {0, 0};
    for (const bool per_sample : {true, false}) {
        Scene s;
        s.light("0.2", "0.8");
        s.set("sample-distance", "0.1");
        s.set("sample-gradients", per_sample ? "true" : "false");
        s.look_along_z(g.volume, 16.0);
        const RenderedImage im = s.render(g, tf, 128, 128);
        double sum = 0;
        int count = 0;
        for (uint32_t y = 0; y < 128; ++y)
            for (uint32_t x = 0; x < 128; ++x) {
                const double px = (x + 0.5) / 4.0 - 16.0, py = (y + 0.5) / 4.0 - 16.0;
                const double r2 = px * px + py * py;
                if (r2 > 10.0 * 10.0) // away from the silhouette, where rays graze
                    continue;
                const double nz = std::sqrt(12.0 * 12.0 - r2) / 12.0;
                const double d = pixel(im, x, y)[0] - (0.2 + 0.8 * nz);
                sum += d * d;
                ++count;
            }
        ASSERT_GT(count, 1000);
        error[per_sample ? 0 : 1] = std::sqrt(sum / count);
    }
    EXPECT_LT(error[0], 0.006) << "per sample";
    EXPECT_LT(error[0], 0.4 * error[1]) << "per sample " << error[0] << ", per voxel " << error[1];
}

// A homogeneous volume (opacity per mm known) seen along z with jitter: a
// ray enters through the face k = 0 and leaves through k = n - 1, so its
// opacity is 1 - (1 - a)^(chord), the chord n - 1 mm, for every pixel
// whatever its start offset.
TEST(SampleFaces, ARayThroughTheFieldOfViewsFacesIntegratesExactlyItsChord)
{
    constexpr int64_t n = 24;
    Grid g{allocate(n, n, n), {}, {}, {}};
    std::fill(g.volume.as<float>(), g.volume.as<float>() + n * n * n, 50.0f);
    TransferFunctions tf(1, kLut, 1.0);
    constant(tf, 0, {1, 1, 1}, 0.08f);
    Scene s;
    s.set("jitter", "true");
    s.look_along_z(g.volume, 6.0); // well inside the x-y faces
    const RenderedImage im = s.render(g, tf, 64, 64);
    const double expected = 1.0 - std::pow(1.0 - 0.08, n - 1.0);
    double worst = 0;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            worst = std::max(worst, std::fabs(pixel(im, x, y)[3] - expected));
    // Without the faces' partial steps a ray's opacity depends on how many
    // lattice points its jitter puts in the chord: off by up to a sample
    // (0.08 * 0.16 of transmittance left, 0.013).
    EXPECT_LT(worst, 2e-3);
}

// An opaque floor (k >= 30) with a trench 6 voxels wide and 8 deep along
// j, seen from above: the occlusion rays from the trench's floor meet its
// walls (visibility at the floor of 0.3, the clamp), those from the open
// floor meet nothing.
TEST(SampleOcclusion, TheFloorOfATrenchDarkensAnOpenFloorDoesNot)
{
    constexpr int64_t n = 48;
    Grid g{allocate(n, n, n), {}, {}, {}};
    for (int64_t k = 0; k < n; ++k)
        for (int64_t j = 0; j < n; ++j)
            for (int64_t i = 0; i < n; ++i) {
                const bool trench = i >= 21 && i <= 26 && k < 38;
                g.volume.as<float>()[i + n * (j + n * k)] = k >= 30 && !trench ? 100.0f : 0.0f;
            }
    TransferFunctions tf(1, kLut, 1.0);
    opaque_from(tf, 50.0, 100.0);
    float trench[2], open[2];
    for (const bool occluded : {false, true}) {
        Scene s;
        s.light("0.3", "0.7");
        s.set("ambient-occlusion", occluded ? "1" : "0");
        s.look_along_z(g.volume, 24.0); // 2 pixels a voxel; x = 23.5 at column 47
        const RenderedImage im = s.render(g, tf, 96, 96);
        trench[occluded] = pixel(im, 47, 48)[0];
        open[occluded] = pixel(im, 48 + 31, 48)[0]; // x = 8
    }
    EXPECT_GT(trench[0], 0.95f);
    EXPECT_GT(open[0], 0.95f);
    EXPECT_LT(trench[1], 0.5f * trench[0]);
    EXPECT_NEAR(open[1], open[0], 0.02f);
}

} // namespace
} // namespace arbor
