// The CPU ray caster through the ABI: the analytic slab (alpha = 1 -
// exp(-kappa L)), label-aware classification of equal values, the camera's
// orientation, depth of the first half-opaque hit, refusal of labels
// without transfer functions; and arbor.renderer/2: tiles that join into the
// full frame, a coarse pass close to the full one, supersampling that
// converges, revisions that decide what is rebuilt, cancellation that
// leaves old or final pixels.
#include "plugin_fixture.hpp"
#include "image_psnr.hpp"

#include "core/cancelled.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace arbor {
namespace {

constexpr int64_t kN = 64;
constexpr uint32_t kLut = 256;

Volume cube(const std::function<float(int64_t, int64_t, int64_t)> &value)
{
    Geometry g;
    g.dims = {kN, kN, kN};
    g.spacing = {1, 1, 1};
    g.origin = {0, 0, 0};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t j = 0; j < kN; ++j)
            for (int64_t i = 0; i < kN; ++i)
                v.as<float>()[i + kN * (j + kN * k)] = value(i, j, k);
    return v;
}

// Over [0, 100]: transparent below 50, colour `rgb` with opacity `alpha` per mm above.
void step_function(TransferFunctions &tf, uint32_t b, std::array<float, 3> rgb, float alpha)
{
    std::vector<float> lut(kLut * 4);
    for (uint32_t i = 0; i < kLut; ++i) {
        const double value = 100.0 * i / (kLut - 1);
        for (int c = 0; c < 3; ++c)
            lut[4 * i + c] = rgb[c];
        lut[4 * i + 3] = value >= 50.0 ? alpha : 0.0f;
    }
    tf.assign(b, {0.0, 100.0}, lut.data());
}

struct Scene {
    PluginInstance renderer = test::built_plugins().create("org.arbor.renderer.cpu-raycast");
    arbor_camera camera{};
    float background[4] = {0, 0, 0, 0};

    Scene()
    {
        set("shading", "false");
        set("jitter", "false");
        set("boundary-emphasis", "0"); // the analytic cases are plain emission and absorption
        camera.struct_size = sizeof camera;
        camera.projection = ARBOR_PROJECTION_ORTHOGRAPHIC;
        camera.parallel_scale = kN / 2.0;
    }
    void set(const std::string &param, const std::string &text)
    {
        renderer.set_param(param, parse_param_value(*renderer.find_param(param), text).value);
    }
    // Looking along +z (from k = 0 towards k = n - 1), +y up.
    void look_along_z()
    {
        const double c = (kN - 1) / 2.0;
        camera.position[0] = c, camera.position[1] = c, camera.position[2] = -200;
        camera.focal_point[0] = c, camera.focal_point[1] = c, camera.focal_point[2] = c;
        camera.view_up[0] = 0, camera.view_up[1] = 1, camera.view_up[2] = 0;
    }
    RenderedImage render(const Volume &v, const TransferFunctions &tf, const std::vector<uint32_t> *labels = nullptr)
    {
        const arbor_volume view = v.view();
        arbor_label_map map{};
        map.struct_size = sizeof map;
        map.label_count = tf.branch_count();
        map.dims[0] = map.dims[1] = map.dims[2] = kN;
        if (labels)
            map.labels = labels->data();
        arbor_render_request r{};
        r.struct_size = sizeof r;
        r.volume = &view;
        r.labels = labels ? &map : nullptr;
        r.transfer_functions = &tf.record();
        r.camera = &camera;
        std::copy(background, background + 4, r.background);
        r.volume_revision = ++revision;
        r.labels_revision = revision;
        return render_image(renderer, r, 64, 64);
    }
    uint64_t revision = 0;
};

const float *pixel(const RenderedImage &im, uint32_t x, uint32_t y)
{
    return &im.rgba[(std::size_t{y} * im.width + x) * 4];
}

TEST(CpuRayCaster, HomogeneousSlabGivesTheExponentialAlpha)
{
    // Value 100 for k in [20, 43]: with trilinear samples the 50-crossings
    // are at k = 19.5 and 43.5, a slab L = 24 mm thick.
    const Volume v = cube([](int64_t, int64_t, int64_t k) { return k >= 20 && k <= 43 ? 100.0f : 0.0f; });
    for (float alpha : {0.02f, 0.05f, 0.1f}) {
        for (double unit : {1.0, 4.0})
            for (const char *step : {"0.5", "0.25"}) {
                TransferFunctions tf(1, kLut, unit);
                step_function(tf, 0, {1, 1, 1}, alpha);
                Scene s;
                s.set("sample-distance", step);
                s.set("termination", "1");
                s.look_along_z();
                const RenderedImage im = s.render(v, tf);
                const double kappa = -std::log(1.0 - alpha) / unit;
                const double expected = 1.0 - std::exp(-kappa * 24.0);
                EXPECT_NEAR(pixel(im, 32, 32)[3], expected, 0.015)
                    << "alpha " << alpha << " per " << unit << " mm, step " << step;
            }
    }
}

TEST(CpuRayCaster, EqualValuesInDifferentBranchesGetTheirOwnColours)
{
    // Two blobs of the same value, left (small i) and right (large i).
    const auto in_blob = [](int64_t i, int64_t j, int64_t k, int64_t ci) {
        return (i - ci) * (i - ci) + (j - 32) * (j - 32) + (k - 32) * (k - 32) < 81;
    };
    const Volume v = cube([&](int64_t i, int64_t j, int64_t k) {
        return in_blob(i, j, k, 16) || in_blob(i, j, k, 48) ? 80.0f : 0.0f;
    });
    std::vector<uint32_t> labels(kN * kN * kN, 0);
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t j = 0; j < kN; ++j)
            for (int64_t i = 0; i < kN; ++i)
                labels[i + kN * (j + kN * k)] = i < 32 ? 1 : 2;
    TransferFunctions tf(3, kLut, 1.0);
    step_function(tf, 0, {1, 1, 1}, 0.0f);
    step_function(tf, 1, {1, 0, 0}, 0.5f);
    step_function(tf, 2, {0, 0, 1}, 0.5f);
    Scene s;
    s.look_along_z();
    const RenderedImage im = s.render(v, tf, &labels);
    // Looking along +z with +y up, +x points to the image's left.
    const float *left = pixel(im, 48, 31), *right = pixel(im, 16, 31);
    EXPECT_GT(left[3], 0.9f);
    EXPECT_GT(right[3], 0.9f);
    EXPECT_GT(left[0], 0.8f);
    EXPECT_LT(left[2], 0.1f);
    EXPECT_GT(right[2], 0.8f);
    EXPECT_LT(right[0], 0.1f);
    // Without labels both blobs take function 0.
    TransferFunctions one(1, kLut, 1.0);
    step_function(one, 0, {0, 1, 0}, 0.5f);
    const RenderedImage plain = s.render(v, one);
    EXPECT_GT(pixel(plain, 16, 31)[1], 0.8f);
    EXPECT_GT(pixel(plain, 48, 31)[1], 0.8f);
}

// Visibility per label (Correa and Ma): on a ray the contributions T * alpha
// of its samples add up to the ray's opacity, so over the image the labels'
// visibilities add up to the sum of the pixels' alpha (transparent
// background); and a structure behind another is seen through what the
// front one leaves.
TEST(CpuRayCaster, VisibilityOfTheLabelsAddsUpToTheImagesOpacity)
{
    // Two slabs along z, one behind the other; the front one is label 1.
    const Volume v = cube([](int64_t, int64_t, int64_t k) { return (k >= 10 && k <= 20) || (k >= 40 && k <= 50) ? 100.0f : 0.0f; });
    std::vector<uint32_t> labels(kN * kN * kN, 0);
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t i = 0; i < kN * kN; ++i)
            labels[static_cast<std::size_t>(i + kN * kN * k)] = k < 32 ? 1 : 2;
    for (float front_alpha : {0.05f, 0.2f, 0.6f}) {
        TransferFunctions tf(3, kLut, 1.0);
        step_function(tf, 0, {1, 1, 1}, 0.0f);
        step_function(tf, 1, {1, 0, 0}, front_alpha);
        step_function(tf, 2, {0, 0, 1}, 0.1f);
        Scene s;
        s.set("termination", "1");
        s.look_along_z();
        const RenderedImage im = s.render(v, tf, &labels);
        ASSERT_EQ(im.label_visibility.size(), 3u);
        double alpha_sum = 0;
        for (std::size_t p = 0; p < std::size_t{im.width} * im.height; ++p)
            alpha_sum += im.rgba[4 * p + 3];
        const double total = im.label_visibility[0] + im.label_visibility[1] + im.label_visibility[2];
        EXPECT_NEAR(total, alpha_sum, 1e-3 * alpha_sum) << front_alpha;
        EXPECT_EQ(im.label_visibility[0], 0.0);
        // Per ray: the front slab keeps 1 - (1 - a1)^L1 of it, the back one
        // gets what passes: (1 - that) * (1 - (1 - a2)^L2).
        const double front = 1 - std::pow(1 - front_alpha, 11.0), back = (1 - front) * (1 - std::pow(0.9, 11.0));
        EXPECT_NEAR(im.label_visibility[1] / total, front / (front + back), 0.03) << front_alpha;
    }
}

// Boundary emphasis: a homogeneous slab's interior thins out (its faces keep
// their opacity), by at most the strength; 0 turns it off.
TEST(CpuRayCaster, BoundaryEmphasisThinsHomogeneousInteriors)
{
    const Volume v = cube([](int64_t, int64_t, int64_t k) { return k >= 10 && k <= 53 ? 100.0f : 0.0f; });
    TransferFunctions tf(1, kLut, 1.0);
    step_function(tf, 0, {1, 1, 1}, 0.05f);
    double alpha[3];
    const double strengths[3] = {0.0, 0.5, 1.0};
    for (int s = 0; s < 3; ++s) {
        Scene scene;
        scene.set("termination", "1");
        scene.set("boundary-emphasis", std::to_string(strengths[s]));
        scene.look_along_z();
        alpha[s] = pixel(scene.render(v, tf), 32, 32)[3];
    }
    EXPECT_GT(alpha[0], alpha[1]);
    EXPECT_GT(alpha[1], alpha[2]);
    // The interior (44 voxels) at half opacity, the faces whole: the optical
    // depth stays above half of it.
    EXPECT_GT(-std::log(1 - alpha[1]), 0.5 * -std::log(1 - alpha[0]));
    EXPECT_GT(alpha[2], 0.0); // the faces stay
}

TEST(CpuRayCaster, OrbitCameraShowsThePatientsLeftOnTheRightFromTheFront)
{
    // A blob at +x (the patient's left in LPS) and a blob at +z (superior).
    Geometry g;
    g.dims = {kN, kN, kN};
    g.spacing = {1, 1, 1};
    const Volume v = cube([](int64_t i, int64_t j, int64_t k) {
        const bool left = (i - 50) * (i - 50) + (j - 32) * (j - 32) + (k - 32) * (k - 32) < 36;
        const bool top = (i - 32) * (i - 32) + (j - 32) * (j - 32) + (k - 52) * (k - 52) < 36;
        return left || top ? 100.0f : 0.0f;
    });
    TransferFunctions tf(1, kLut, 1.0);
    step_function(tf, 0, {1, 1, 1}, 0.8f);
    Scene s;
    Orbit front;
    s.camera = orbit_camera(v.geometry(), front);
    const RenderedImage im = s.render(v, tf);
    double sx = 0, sy = 0, w = 0, tx = 0, ty = 0, tw = 0;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const float a = pixel(im, x, y)[3];
            if (a < 0.5f)
                continue;
            if (x > 32) { // the left blob
                sx += x, sy += y, w += 1;
            } else {
                tx += x, ty += y, tw += 1;
            }
        }
    ASSERT_GT(w, 0);
    ASSERT_GT(tw, 0);
    EXPECT_NEAR(sy / w, 31.5, 3.0);  // level with the centre
    EXPECT_LT(ty / tw, 20.0);        // superior is up
    EXPECT_NEAR(tx / tw, 31.5, 3.0); // centred
    // Depth of the first half-opaque hit: the camera-facing surface of the blob.
    const arbor_camera &c = s.camera;
    const double to_centre = std::hypot(c.position[0] - 31.5, c.position[1] - 31.5, c.position[2] - 31.5);
    const float d = im.depth[32 * 64 + static_cast<uint32_t>(sx / w)];
    EXPECT_TRUE(std::isfinite(d));
    EXPECT_LT(d, to_centre + 1);
    EXPECT_GT(d, to_centre - 40);
}

TEST(CpuRayCaster, LabelsWithoutTransferFunctionsAreRefused)
{
    const Volume v = cube([](int64_t, int64_t, int64_t) { return 1.0f; });
    std::vector<uint32_t> labels(kN * kN * kN, 0);
    labels[100] = 5;
    TransferFunctions tf(2, kLut, 1.0);
    step_function(tf, 0, {1, 1, 1}, 0.5f);
    step_function(tf, 1, {1, 1, 1}, 0.5f);
    Scene s;
    s.look_along_z();
    try {
        s.render(v, tf, &labels);
        FAIL() << "label 5 accepted with 2 transfer functions";
    } catch (const PluginError &e) {
        EXPECT_NE(std::string(e.what()).find("label 5"), std::string::npos) << e.what();
    }
}

// A lit, labelled ball in a shell: something with edges for the passes to
// get right or wrong.
struct Interactive {
    Volume volume = cube([](int64_t i, int64_t j, int64_t k) {
        const double r = std::hypot(i - 31.5, j - 31.5, k - 31.5);
        return static_cast<float>(r < 12 ? 100 : r > 22 && r < 26 ? 80 : 10);
    });
    std::vector<uint32_t> labels = std::vector<uint32_t>(kN * kN * kN, 0);
    TransferFunctions tf{2, kLut, 1.0};
    Scene scene;
    arbor_volume view = volume.view();
    arbor_label_map map{};
    arbor_render_request request{};

    Interactive()
    {
        for (int64_t k = 0; k < kN; ++k)
            for (int64_t j = 0; j < kN; ++j)
                for (int64_t i = 0; i < kN; ++i)
                    labels[static_cast<std::size_t>(i + kN * (j + kN * k))] =
                        std::hypot(i - 31.5, j - 31.5, k - 31.5) < 17 ? 1u : 0u;
        step_function(tf, 0, {0.9f, 0.8f, 0.6f}, 0.15f);
        step_function(tf, 1, {0.8f, 0.2f, 0.2f}, 0.4f);
        scene.set("shading", "true");
        scene.set("jitter", "true");
        scene.set("coarse-pixels", "4"); // not chosen from this machine's speed

        scene.camera.projection = ARBOR_PROJECTION_PERSPECTIVE;
        scene.camera.view_angle = 30;
        const double c = (kN - 1) / 2.0;
        scene.camera.position[0] = c + 60, scene.camera.position[1] = c - 90, scene.camera.position[2] = c + 40;
        scene.camera.focal_point[0] = c, scene.camera.focal_point[1] = c, scene.camera.focal_point[2] = c;
        scene.camera.view_up[2] = 1;
        map.struct_size = sizeof map;
        map.label_count = 2;
        map.dims[0] = map.dims[1] = map.dims[2] = kN;
        map.labels = labels.data();
        request.struct_size = sizeof request;
        request.volume = &view;
        request.labels = &map;
        request.transfer_functions = &tf.record();
        request.camera = &scene.camera;
        request.volume_revision = request.labels_revision = 7;
    }
    RenderedImage frame(uint32_t w, uint32_t h) const
    {
        RenderedImage f;
        f.width = w;
        f.height = h;
        f.rgba.assign(std::size_t{w} * h * 4, 0.0f);
        f.depth.assign(std::size_t{w} * h, 0.0f);
        return f;
    }
    RenderedImage render(FramePass pass = {}, uint32_t w = 96, uint32_t h = 80)
    {
        pass.transfer_functions_revision = tf_revision;
        return render_image(scene.renderer, request, w, h, nullptr, {}, pass);
    }
    uint64_t tf_revision = 1;
};

TEST(CpuRayCaster2, OffersTheInteractiveInterface)
{
    Interactive s;
    EXPECT_TRUE(renders_passes(s.scene.renderer));
}

TEST(CpuRayCaster2, TilesJoinIntoTheFullFrameExactly)
{
    Interactive s;
    for (const arbor_render_pass p : {ARBOR_RENDER_PASS_FULL, ARBOR_RENDER_PASS_COARSE}) {
        const RenderedImage whole = s.render({p});
        RenderedImage tiled = s.frame(96, 80);
        std::vector<double> visibility(2, 0.0);
        // Uneven tiles, not aligned to the coarse pass's 4 x 4 blocks.
        for (uint32_t y = 0; y < 80; y += 27)
            for (uint32_t x = 0; x < 96; x += 37) {
                render_region(s.scene.renderer, s.request, tiled,
                              {x, y, std::min(37u, 96 - x), std::min(27u, 80 - y)}, {p, 0, s.tf_revision});
                for (std::size_t l = 0; l < 2; ++l)
                    visibility[l] += tiled.label_visibility[l];
            }
        EXPECT_EQ(tiled.rgba, whole.rgba) << "pass " << p;
        if (p == ARBOR_RENDER_PASS_FULL) {
            EXPECT_EQ(tiled.depth, whole.depth);
            for (std::size_t l = 0; l < 2; ++l)
                EXPECT_NEAR(visibility[l], whole.label_visibility[l], 1e-6 * (1 + whole.label_visibility[l]));
        }
    }
}

TEST(CpuRayCaster2, TheCoarsePassIsCloseToTheFullOneAndFaster)
{
    Interactive s;
    const RenderedImage full = s.render({}, 256, 256);
    const RenderedImage coarse = s.render({ARBOR_RENDER_PASS_COARSE}, 256, 256);
    const double db = test::psnr(coarse, full);
    EXPECT_GT(db, 24.0) << "coarse against full: " << db << " dB";
    EXPECT_LT(db, 80.0) << "the coarse pass is the full one";
    // Visibility is measured on the coarse pass too, scaled to the frame.
    double total = 0, full_total = 0;
    for (std::size_t l = 0; l < 2; ++l) {
        total += coarse.label_visibility[l];
        full_total += full.label_visibility[l];
    }
    EXPECT_NEAR(total, full_total, 0.1 * full_total);
}

TEST(CpuRayCaster2, OnALargeVolumeTheCoarsePassStaysClose)
{
    // 168^3 voxels, larger than the caches: the rays prefetch ahead of
    // themselves.  A labelled ball in a shell, as above.
    constexpr int64_t n = 168;
    Geometry g;
    g.dims = {n, n, n};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    std::vector<uint32_t> labels(static_cast<std::size_t>(n * n * n));
    const double c = (n - 1) / 2.0;
    for (int64_t k = 0; k < n; ++k)
        for (int64_t j = 0; j < n; ++j)
            for (int64_t i = 0; i < n; ++i) {
                const double r = std::hypot(i - c, j - c, k - c);
                const std::size_t at = static_cast<std::size_t>(i + n * (j + n * k));
                v.as<float>()[at] = static_cast<float>(r < 30 ? 100 : r > 58 && r < 66 ? 80 : 10);
                labels[at] = r < 44 ? 1u : 0u;
            }
    Interactive s;
    s.view = v.view();
    for (int a = 0; a < 3; ++a)
        s.map.dims[a] = n;
    s.map.labels = labels.data();
    for (int a = 0; a < 3; ++a) {
        s.scene.camera.focal_point[a] = c;
        s.scene.camera.position[a] = c + (a == 0 ? 150 : a == 1 ? -230 : 100);
    }
    const RenderedImage full = s.render({}, 256, 256);
    const RenderedImage coarse = s.render({ARBOR_RENDER_PASS_COARSE}, 256, 256);
    const double db = test::psnr(coarse, full);
    // Hard-edged step functions, a voxel per 1.5 pixels; a grid misplaced
    // by half a voxel gives 15.
    EXPECT_GT(db, 20.0) << "coarse against full: " << db << " dB";
    EXPECT_LT(db, 80.0);
    // The shell and the ball both show, in their own colours: the centre
    // pixel is reddish (the ball, label 1), the rim's yellowish (label 0).
    const float *centre = pixel(coarse, 128, 128), *full_centre = pixel(full, 128, 128);
    EXPECT_GT(centre[0], centre[2]);
    EXPECT_NEAR(centre[3], full_centre[3], 0.1);
    // Tiles join exactly.
    RenderedImage tiled = s.frame(256, 256);
    for (uint32_t y = 0; y < 256; y += 100)
        for (uint32_t x = 0; x < 256; x += 90)
            render_region(s.scene.renderer, s.request, tiled, {x, y, std::min(90u, 256 - x), std::min(100u, 256 - y)},
                          {ARBOR_RENDER_PASS_COARSE, 0, s.tf_revision});
    EXPECT_EQ(tiled.rgba, coarse.rgba);
}

TEST(CpuRayCaster2, OnAnAnisotropicVolumeTheCoarsePassKeepsItsSlices)
{
    // A CT's grid, 0.5 mm pixels and 1.5 mm slices: a plate one slice thick
    // every fourth slice.  A coarse pass that averaged pairs of slices (3 mm)
    // would drop the plates under the transfer function's step (45 < 50).
    constexpr int64_t nx = 320, nz = 48;
    Geometry g;
    g.dims = {nx, nx, nz};
    g.spacing = {0.5, 0.5, 1.5};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    std::vector<uint32_t> labels(static_cast<std::size_t>(nx * nx * nz), 0u);
    const double c = (nx - 1) / 2.0;
    for (int64_t k = 0; k < nz; ++k)
        for (int64_t j = 0; j < nx; ++j)
            for (int64_t i = 0; i < nx; ++i)
                v.as<float>()[static_cast<std::size_t>(i + nx * (j + nx * k))] =
                    k % 4 == 1 && std::hypot(i - c, j - c) < 120 ? 90.0f : 0.0f;
    Interactive s;
    s.view = v.view();
    s.map.dims[0] = s.map.dims[1] = nx;
    s.map.dims[2] = nz;
    s.map.labels = labels.data();
    const double centre[3] = {c * 0.5, c * 0.5, (nz - 1) / 2.0 * 1.5};
    for (int a = 0; a < 3; ++a) {
        s.scene.camera.focal_point[a] = centre[a];
        s.scene.camera.position[a] = centre[a] + (a == 0 ? 90 : a == 1 ? -140 : 110);
    }
    const RenderedImage full = s.render({}, 256, 256);
    const RenderedImage coarse = s.render({ARBOR_RENDER_PASS_COARSE}, 256, 256);
    const auto opacity = [](const RenderedImage &image) {
        double sum = 0;
        for (std::size_t p = 3; p < image.rgba.size(); p += 4)
            sum += image.rgba[p];
        return sum;
    };
    ASSERT_GT(opacity(full), 0.1 * 256 * 256) << "the plates are not in the full image";
    EXPECT_NEAR(opacity(coarse), opacity(full), 0.1 * opacity(full));
    EXPECT_GT(test::psnr(coarse, full), 24.0);
}

TEST(CpuRayCaster2, TheCoarsePassChoosesItsRaysFromTheFrameRate)
{
    Interactive s;
    // The images of the extreme fixed choices of pixels per ray, 1024 x 1024.
    std::map<int, std::vector<float>> fixed;
    for (int n : {2, 8}) {
        s.scene.set("coarse-pixels", std::to_string(n));
        fixed[n] = s.render({ARBOR_RENDER_PASS_COARSE}, 1024, 1024).rgba;
    }
    const auto settled = [&](const char *rate) {
        s.scene.set("coarse-pixels", "0");
        s.scene.set("coarse-rate", rate);
        std::vector<float> last;
        for (int i = 0; i < 8; ++i)
            last = s.render({ARBOR_RENDER_PASS_COARSE}, 1024, 1024).rgba;
        return last;
    };
    // An easy rate: as many rays as it allows (one per 2 x 2 pixels).
    EXPECT_EQ(settled("1"), fixed[2]);
    // A rate no machine reaches with a quarter of a million rays (4 ms a
    // frame): fewer rays.
    EXPECT_NE(settled("240"), fixed[2]);
}

TEST(CpuRayCaster2, SupersamplingConvergesAndBlendsOnlyWhatIsThere)
{
    Interactive s;
    RenderedImage image = s.render();
    const RenderedImage once = image;
    // Pass n blends in 1 / (n + 1) of a new sample: the mean change of the
    // image falls like 1 / (n + 1).
    std::vector<double> change;
    for (uint32_t n = 1; n <= 8; ++n) {
        const RenderedImage before = image;
        render_region(s.scene.renderer, s.request, image, {}, {ARBOR_RENDER_PASS_SUPERSAMPLE, n, s.tf_revision});
        double sum = 0;
        for (std::size_t i = 0; i < image.rgba.size(); ++i)
            sum += std::fabs(image.rgba[i] - before.rgba[i]);
        change.push_back(sum / static_cast<double>(image.rgba.size()));
        EXPECT_GT(change.back(), 0.0) << "pass " << n << " changed nothing";
    }
    EXPECT_LT(change[7], 0.5 * change[0]) << "pass 8 moved the image as much as pass 1";
    // The refined image stays the same picture: close to the single sample.
    EXPECT_GT(test::psnr(image, once), 25.0);
    EXPECT_EQ(image.depth, once.depth); // depth is the full pass's
    for (float x : image.rgba)
        ASSERT_TRUE(x >= 0.0f && x <= 1.0f);
}

TEST(CpuRayCaster2, RevisionsDecideWhatIsRebuilt)
{
    Interactive s;
    const RenderedImage a = s.render();
    // New lookup tables under the same revision: the renderer may keep its
    // tables (the host promised nothing changed) - and it does.
    step_function(s.tf, 1, {0.2f, 0.2f, 0.9f}, 0.4f);
    const RenderedImage same = s.render();
    EXPECT_EQ(same.rgba, a.rgba);
    // A new revision: the new colours.
    ++s.tf_revision;
    const RenderedImage changed = s.render();
    EXPECT_LT(test::psnr(changed, a), 30.0);
    // Revision 0 (unknown): contents decide.
    s.tf_revision = 0;
    EXPECT_EQ(s.render().rgba, changed.rgba);
    step_function(s.tf, 1, {0.8f, 0.2f, 0.2f}, 0.4f);
    EXPECT_EQ(s.render().rgba, a.rgba);
}

// Cancels its task once `after` progress reports have come.
struct CancelAfter : ProgressSink {
    explicit CancelAfter(int n) : after(n) {}
    void report(const std::string &, double) override
    {
        if (--after == 0)
            source.request_stop();
    }
    void finish() override {}
    int after;
    std::stop_source source;
};

TEST(CpuRayCaster2, ACancelledPassLeavesOldOrFinalPixels)
{
    Interactive s;
    // One thread: the caller casts every tile in order and sees the stop
    // after its first report, however many cores the machine has (with a
    // pool, the caller's first report can come after the last tile).
    s.scene.set("threads", "1");
    const RenderedImage final_image = s.render({}, 512, 512);
    RenderedImage image = s.frame(512, 512);
    std::fill(image.rgba.begin(), image.rgba.end(), 0.5f); // "before": a grey no ray gives
    CancelAfter sink(1);
    EXPECT_THROW(render_region(s.scene.renderer, s.request, image, {}, {ARBOR_RENDER_PASS_FULL, 0, s.tf_revision}, &sink,
                               sink.source.get_token()),
                 Cancelled);
    std::size_t old = 0, done = 0;
    for (std::size_t p = 0; p < image.rgba.size(); p += 4) {
        const bool is_old = std::equal(&image.rgba[p], &image.rgba[p] + 4, std::array{0.5f, 0.5f, 0.5f, 0.5f}.begin());
        const bool is_final = std::equal(&image.rgba[p], &image.rgba[p] + 4, &final_image.rgba[p]);
        ASSERT_TRUE(is_old || is_final) << "pixel " << p / 4 << " is neither";
        old += is_old;
        done += is_final && !is_old;
    }
    EXPECT_GT(old, 0u) << "cancelled, yet every pixel was rendered";
    EXPECT_GT(done, 0u) << "cancelled after its first report, yet no tile was kept";
}

} // namespace
} // namespace arbor
