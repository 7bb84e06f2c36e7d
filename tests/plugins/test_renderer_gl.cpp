// The OpenGL ray caster against the CPU ray caster, which renders the same
// optical model: the same scenes through both, compared by PSNR (unshaded
// and shaded, with ambient occlusion, labelled, perspective and
// orthographic, the coarse pass),
// visibility per label, tiles that join, supersampling, cancellation, and
// the device it says it renders on.  On this machine that is Mesa's
// llvmpipe through EGL, with no X server; the GL pictures are compared
// loosely (llvmpipe and graphics hardware filter textures with their own
// arithmetic): on llvmpipe they agree to 72-90 dB, the floors are 45-50.
#include "gl_scene.hpp"

#include "core/cancelled.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor {
namespace {

using namespace test::gl_scene;

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

// Slices three times as far apart as the rows: both take the gradient as
// on the volume resampled to isotropic voxels (IsotropicGradient).
TEST(GlRayCaster, MatchesTheCpuRayCasterOnThickSlices)
{
    Pair s({1.0, 1.0, 3.0});
    s.camera.position[2] += 150; // outside the taller volume
    const RenderedImage gl = s.render(s.gl), cpu = s.render(s.cpu);
    EXPECT_GT(test::psnr(gl, cpu), 45.0);
    // Not by accident: each voxel's normals give another picture.
    s.set("sample-gradients", "false");
    EXPECT_LT(test::psnr(s.render(s.gl), cpu), test::psnr(gl, cpu) - 5.0);
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
