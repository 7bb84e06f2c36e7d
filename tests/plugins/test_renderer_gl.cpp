// The OpenGL ray caster against the CPU ray caster, which renders the same
// optical model: the same scenes through both, compared by PSNR (unshaded
// and shaded, with ambient occlusion, labelled, perspective and
// orthographic, the coarse pass),
// visibility per label, tiles that join, supersampling, cancellation, and
// the device it says it renders on.  On this machine that is Mesa's
// llvmpipe through EGL, with no X server; the GL pictures are compared
// loosely (llvmpipe and graphics hardware filter textures with their own
// arithmetic): on llvmpipe they agree to 72-90 dB, the floors are 45-50.
#include "plugin_fixture.hpp"
#include "image_psnr.hpp"

#include "core/cancelled.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor {
namespace {

constexpr int64_t kN = 64;
constexpr uint32_t kLut = 256;
constexpr const char *kGl = "org.arbor.renderer.gl-raycast", *kCpu = "org.arbor.renderer.cpu-raycast";

Volume ball_in_shell()
{
    Geometry g;
    g.dims = {kN, kN, kN};
    g.spacing = {1.0, 0.9, 1.3}; // anisotropic, as scans are
    g.origin = {-20, 10, 5};
    Volume v = Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
    for (int64_t k = 0; k < kN; ++k)
        for (int64_t j = 0; j < kN; ++j)
            for (int64_t i = 0; i < kN; ++i) {
                const double r = std::hypot(i - 31.5, j - 29.0, k - 33.0);
                // A ramp inside the ball, so values between the steps are sampled too.
                v.as<float>()[i + kN * (j + kN * k)] =
                    static_cast<float>(r < 12 ? 70 + 2.5 * (12 - r) : r > 22 && r < 26 ? 80 : 10 + 0.2 * i);
            }
    return v;
}

// Over [0, 100]: a ramp of opacity from 45 up, colour `rgb`.
void ramp_function(TransferFunctions &tf, uint32_t b, std::array<float, 3> rgb, float alpha)
{
    std::vector<float> lut(kLut * 4);
    for (uint32_t i = 0; i < kLut; ++i) {
        const double value = 100.0 * i / (kLut - 1);
        for (int c = 0; c < 3; ++c)
            lut[4 * i + c] = rgb[c] * static_cast<float>(0.6 + 0.4 * value / 100.0);
        lut[4 * i + 3] = value >= 45.0 ? alpha * static_cast<float>(std::min(1.0, (value - 45.0) / 30.0)) : 0.0f;
    }
    tf.assign(b, {0.0, 100.0}, lut.data());
}

struct Pair {
    Volume volume = ball_in_shell();
    std::vector<uint32_t> labels = std::vector<uint32_t>(kN * kN * kN, 0);
    TransferFunctions tf{3, kLut, 1.0};
    PluginInstance gl = test::built_plugins().create(kGl);
    PluginInstance cpu = test::built_plugins().create(kCpu);
    arbor_camera camera{};
    arbor_volume view = volume.view();
    arbor_label_map map{};
    arbor_render_request request{};
    uint64_t tf_revision = 1;

    Pair()
    {
        for (int64_t k = 0; k < kN; ++k)
            for (int64_t j = 0; j < kN; ++j)
                for (int64_t i = 0; i < kN; ++i) {
                    const double r = std::hypot(i - 31.5, j - 29.0, k - 33.0);
                    labels[static_cast<std::size_t>(i + kN * (j + kN * k))] = r < 17 ? (i < 32 ? 1u : 2u) : 0u;
                }
        ramp_function(tf, 0, {0.9f, 0.8f, 0.6f}, 0.12f);
        ramp_function(tf, 1, {0.8f, 0.2f, 0.2f}, 0.5f);
        ramp_function(tf, 2, {0.2f, 0.4f, 0.9f}, 0.5f);
        camera.struct_size = sizeof camera;
        camera.projection = ARBOR_PROJECTION_PERSPECTIVE;
        camera.view_angle = 30;
        const double c[3] = {-20 + 31.5, 10 + 0.9 * 31.5, 5 + 1.3 * 31.5};
        camera.position[0] = c[0] + 70, camera.position[1] = c[1] - 100, camera.position[2] = c[2] + 50;
        for (int a = 0; a < 3; ++a)
            camera.focal_point[a] = c[a];
        camera.view_up[2] = 1;
        map.struct_size = sizeof map;
        map.label_count = 3;
        map.dims[0] = map.dims[1] = map.dims[2] = kN;
        map.labels = labels.data();
        request.struct_size = sizeof request;
        request.volume = &view;
        request.labels = &map;
        request.transfer_functions = &tf.record();
        request.camera = &camera;
        request.volume_revision = request.labels_revision = 3;
        set("coarse-pixels", "4");
    }
    void set(const std::string &param, const std::string &text)
    {
        for (PluginInstance *r : {&gl, &cpu})
            r->set_param(param, parse_param_value(*r->find_param(param), text).value);
    }
    RenderedImage render(PluginInstance &r, FramePass pass = {}, uint32_t w = 160, uint32_t h = 128)
    {
        pass.transfer_functions_revision = tf_revision;
        return render_image(r, request, w, h, nullptr, {}, pass);
    }
    // PSNR of the GL image against the CPU's, this pass.
    double agreement(FramePass pass = {}, uint32_t w = 160, uint32_t h = 128)
    {
        const RenderedImage a = render(gl, pass, w, h), b = render(cpu, pass, w, h);
        return test::psnr(a, b);
    }
};

TEST(GlRayCaster, SaysWhatItRendersOn)
{
    Pair s;
    const RenderDevice gl = render_device(s.gl), cpu = render_device(s.cpu);
    EXPECT_EQ(cpu.kind, ARBOR_DEVICE_CPU);
    EXPECT_NE(cpu.name.find("CPU threads"), std::string::npos) << cpu.name;
    ASSERT_FALSE(gl.name.empty());
    EXPECT_NE(gl.name.find("OpenGL"), std::string::npos) << gl.name;
    // Mesa's software rasteriser says so; hardware says GPU.
    const bool llvmpipe = gl.name.find("llvmpipe") != std::string::npos || gl.name.find("softpipe") != std::string::npos;
    EXPECT_EQ(gl.kind, llvmpipe ? ARBOR_DEVICE_SOFTWARE_GPU : ARBOR_DEVICE_GPU) << gl.name;
    EXPECT_TRUE(renders_passes(s.gl));
}

TEST(GlRayCaster, MatchesTheCpuRayCasterUnshaded)
{
    Pair s;
    s.set("shading", "false");
    s.set("boundary-emphasis", "0");
    s.set("jitter", "false");
    const double db = s.agreement();
    EXPECT_GT(db, 50.0) << db << " dB";
    // Orthographic too, and without labels (one function for all).
    s.camera.projection = ARBOR_PROJECTION_ORTHOGRAPHIC;
    s.camera.parallel_scale = 45;
    EXPECT_GT(s.agreement(), 50.0);
    s.request.labels = nullptr;
    EXPECT_GT(s.agreement(), 50.0);
}

TEST(GlRayCaster, MatchesTheCpuRayCasterShadedWithBoundaryEmphasisAndJitter)
{
    Pair s; // the defaults: shading, boundary emphasis, jitter
    const RenderedImage gl = s.render(s.gl), cpu = s.render(s.cpu);
    const double db = test::psnr(gl, cpu);
    EXPECT_GT(db, 45.0) << db << " dB";
    // Not the same picture by accident: a different light model is far off.
    s.set("shading", "false");
    EXPECT_LT(test::psnr(s.render(s.gl), cpu), db - 5.0);
    // Depth of the first half-opaque sample agrees where both have one.
    double worst = 0;
    std::size_t both = 0;
    for (std::size_t p = 0; p < gl.depth.size(); ++p)
        if (std::isfinite(gl.depth[p]) && std::isfinite(cpu.depth[p])) {
            ++both;
            worst = std::max(worst, static_cast<double>(std::fabs(gl.depth[p] - cpu.depth[p])));
        }
    EXPECT_GT(both, gl.depth.size() / 10);
    EXPECT_LT(worst, 2.0) << "mm";
}

TEST(GlRayCaster, MatchesTheCpuRayCasterWithAmbientOcclusion)
{
    Pair s;
    const RenderedImage plain = s.render(s.gl);
    s.set("ambient-occlusion", "0.8");
    const RenderedImage gl = s.render(s.gl), cpu = s.render(s.cpu);
    EXPECT_GT(test::psnr(gl, cpu), 45.0);
    EXPECT_LT(test::psnr(gl, plain), 40.0) << "the occlusion darkened nothing";
}

TEST(GlRayCaster, MeasuresTheVisibilityOfEachLabelAsTheCpuRayCasterDoes)
{
    Pair s;
    const RenderedImage gl = s.render(s.gl), cpu = s.render(s.cpu);
    double total = 0;
    for (std::size_t l = 0; l < 3; ++l) {
        EXPECT_GT(cpu.label_visibility[l], 0.0);
        EXPECT_NEAR(gl.label_visibility[l], cpu.label_visibility[l], 0.02 * cpu.label_visibility[l] + 0.5)
            << "label " << l;
        total += gl.label_visibility[l];
    }
    // The labels' shares add up to the image's opacity (no background here).
    double alpha = 0;
    for (std::size_t p = 3; p < gl.rgba.size(); p += 4)
        alpha += gl.rgba[p];
    EXPECT_NEAR(total, alpha, 1e-3 * alpha);
}

TEST(GlRayCaster, TilesJoinIntoTheFullFrame)
{
    Pair s;
    for (const arbor_render_pass p : {ARBOR_RENDER_PASS_FULL, ARBOR_RENDER_PASS_COARSE}) {
        const RenderedImage whole = s.render(s.gl, {p}, 96, 80);
        RenderedImage tiled;
        tiled.width = 96;
        tiled.height = 80;
        tiled.rgba.assign(96 * 80 * 4, 0.0f);
        tiled.depth.assign(96 * 80, 0.0f);
        for (uint32_t y = 0; y < 80; y += 27)
            for (uint32_t x = 0; x < 96; x += 37)
                render_region(s.gl, s.request, tiled, {x, y, std::min(37u, 96 - x), std::min(27u, 80 - y)},
                              {p, 0, s.tf_revision});
        EXPECT_GT(test::psnr(tiled, whole), 90.0) << "pass " << p;
    }
}

TEST(GlRayCaster, TheCoarsePassMatchesTheCpuCoarsePass)
{
    Pair s;
    const double db = s.agreement({ARBOR_RENDER_PASS_COARSE}, 256, 256);
    EXPECT_GT(db, 45.0) << db << " dB";
    const RenderedImage coarse = s.render(s.gl, {ARBOR_RENDER_PASS_COARSE}, 256, 256);
    const RenderedImage full = s.render(s.gl, {}, 256, 256);
    EXPECT_LT(test::psnr(coarse, full), 80.0) << "the coarse pass is the full one";
}

TEST(GlRayCaster, SupersamplingConvergesAsOnTheCpu)
{
    Pair s;
    RenderedImage gl = s.render(s.gl), cpu = s.render(s.cpu);
    const RenderedImage first = gl;
    for (uint32_t n = 1; n <= 4; ++n) {
        render_region(s.gl, s.request, gl, {}, {ARBOR_RENDER_PASS_SUPERSAMPLE, n, s.tf_revision});
        render_region(s.cpu, s.request, cpu, {}, {ARBOR_RENDER_PASS_SUPERSAMPLE, n, s.tf_revision});
    }
    EXPECT_LT(test::psnr(gl, first), 90.0) << "supersampling changed nothing";
    EXPECT_GT(test::psnr(gl, cpu), 45.0);
    EXPECT_EQ(gl.depth, first.depth); // depth is the full pass's
}

// Cancels its task at the first progress report.
struct CancelAtOnce : ProgressSink {
    void report(const std::string &, double) override { source.request_stop(); }
    void finish() override {}
    std::stop_source source;
};

TEST(GlRayCaster, ACancelledPassLeavesThePixelsAsTheyWere)
{
    Pair s;
    RenderedImage image;
    image.width = 256;
    image.height = 256;
    image.rgba.assign(256 * 256 * 4, 0.5f);
    image.depth.assign(256 * 256, 0.0f);
    CancelAtOnce sink;
    EXPECT_THROW(render_region(s.gl, s.request, image, {}, {ARBOR_RENDER_PASS_FULL, 0, s.tf_revision}, &sink,
                               sink.source.get_token()),
                 Cancelled);
    for (float x : image.rgba)
        ASSERT_EQ(x, 0.5f);
    // And the next call renders as if nothing happened.
    EXPECT_GT(test::psnr(s.render(s.gl, {}, 256, 256), s.render(s.cpu, {}, 256, 256)), 45.0);
}

TEST(GlRayCaster, NewTransferFunctionsUnderANewRevisionAreRendered)
{
    Pair s;
    const RenderedImage a = s.render(s.gl);
    ramp_function(s.tf, 1, {0.1f, 0.9f, 0.1f}, 0.5f);
    ++s.tf_revision;
    const RenderedImage b = s.render(s.gl);
    EXPECT_LT(test::psnr(a, b), 35.0);
    EXPECT_GT(test::psnr(b, s.render(s.cpu)), 45.0);
}

TEST(GlRayCaster, NewLabelsUnderANewRevisionAreRendered)
{
    Pair s;
    const RenderedImage a = s.render(s.gl);
    for (uint32_t &l : s.labels) // the two halves of the ball swap colours
        l = l == 1 ? 2u : l == 2 ? 1u : l;
    ++s.request.labels_revision;
    const RenderedImage b = s.render(s.gl);
    EXPECT_LT(test::psnr(a, b), 35.0);
    EXPECT_GT(test::psnr(b, s.render(s.cpu)), 45.0);
}

} // namespace
} // namespace arbor
