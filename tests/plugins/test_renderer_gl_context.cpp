// The OpenGL ray caster drawing into the host's own context
// (arbor.renderer-gl/1): a hidden GLFW window's context, made as the
// workstation makes its own (GLX under Xvfb here), is current on the test's
// thread; the passes the plugin draws into a texture of it are read back
// and compared with the same plugin's offscreen images (its own EGL
// context) and with the CPU ray caster's: full, coarse, supersampled,
// tiles, an 8-bit texture, cancellation and release.
#include "gl_scene.hpp"

#include "core/cancelled.hpp"
#include "counting_surface.hpp"
#include "pipeline/progressive_view.hpp"
#include "host/host_services.hpp"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

namespace arbor {
namespace {

using namespace test::gl_scene;

constexpr uint32_t kW = 160, kH = 128;

// A hidden window's OpenGL 3.3 core context, current on this thread.
class HostContext {
public:
    // Tried three times: under a loaded Xvfb shared by the whole test run a
    // window has (once in hundreds of runs) not been had at the first try.
    // What GLFW said of the last failure is kept for the test's message.
    HostContext()
    {
        for (int attempt = 0; attempt < 3 && !window_; ++attempt) {
            if (attempt > 0)
                std::this_thread::sleep_for(std::chrono::milliseconds(250));
            if (!glfwInit()) {
                remember_error();
                continue;
            }
            glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
            glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
            glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
            glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
            glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
            window_ = glfwCreateWindow(64, 64, "arbor test", nullptr, nullptr);
            if (!window_) {
                remember_error();
                glfwTerminate();
            }
        }
        if (window_)
            glfwMakeContextCurrent(window_);
    }
    // GLFW's description of why no context was made ("" when one was).
    const std::string &error() const { return error_; }
    ~HostContext()
    {
        for (GLuint t : textures_)
            glDeleteTextures(1, &t);
        if (window_) {
            glfwMakeContextCurrent(nullptr);
            glfwDestroyWindow(window_);
        }
        glfwTerminate();
    }
    HostContext(const HostContext &) = delete;
    HostContext &operator=(const HostContext &) = delete;

    explicit operator bool() const { return window_ != nullptr; }

    // A frame-sized texture, every texel `fill`.
    GlFrame texture(GLenum format = GL_RGBA32F, float fill = 0.0f, uint32_t w = kW, uint32_t h = kH)
    {
        GLuint t = 0;
        glGenTextures(1, &t);
        textures_.push_back(t);
        glBindTexture(GL_TEXTURE_2D, t);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        const std::vector<float> texels(std::size_t{w} * h * 4, fill);
        glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(format), static_cast<GLsizei>(w), static_cast<GLsizei>(h), 0,
                     GL_RGBA, GL_FLOAT, texels.data());
        return {t, w, h};
    }

    // Its texels, row 0 first, as an image.
    static RenderedImage read(const GlFrame &frame)
    {
        RenderedImage image;
        image.width = frame.width;
        image.height = frame.height;
        image.rgba.assign(std::size_t{frame.width} * frame.height * 4, 0.0f);
        glFinish();
        glBindTexture(GL_TEXTURE_2D, frame.texture);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, image.rgba.data());
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
        return image;
    }

private:
    void remember_error()
    {
        const char *description = nullptr;
        const int code = glfwGetError(&description);
        error_ = "GLFW error " + std::to_string(code) + ": " + (description ? description : "(none)");
    }

    GLFWwindow *window_ = nullptr;
    std::string error_;
    std::vector<GLuint> textures_;
};

// The scene, with the host's context current, released before the
// renderer dies (as the contract asks).
struct InContext : Pair {
    HostContext context;
    ~InContext()
    {
        if (context)
            release_gl(gl);
    }
    void draw(const GlFrame &frame, arbor_render_pass pass, uint32_t sample = 0, Region region = {},
              ProgressSink *progress = nullptr, std::stop_token stop = {})
    {
        render_gl(gl, request, frame, region, {pass, sample, tf_revision}, progress, std::move(stop));
    }
};

#define REQUIRE_CONTEXT(s)                                                                                             \
    if (!std::getenv("DISPLAY"))                                                                                       \
        GTEST_SKIP() << "no X display: run under xvfb-run (ctest does)";                                               \
    ASSERT_TRUE(s.context) << "no OpenGL 3.3 core context from GLFW on this display: " << s.context.error()

TEST(GlRayCasterInContext, OffersTheInterfaceTheCpuRayCasterDoesNot)
{
    Pair s;
    EXPECT_TRUE(renders_into_gl(s.gl));
    EXPECT_FALSE(renders_into_gl(s.cpu));
}

TEST(GlRayCasterInContext, TheFullPassEqualsTheOffscreenImage)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture();
    s.draw(frame, ARBOR_RENDER_PASS_FULL);
    const RenderedImage drawn = HostContext::read(frame);
    const double own = test::psnr(drawn, s.render(s.gl, {}, kW, kH));
    const double cpu = test::psnr(drawn, s.render(s.cpu, {}, kW, kH));
    EXPECT_GT(own, 80.0) << own << " dB from the plugin's offscreen image";
    EXPECT_GT(cpu, 45.0) << cpu << " dB from the CPU ray caster";
    // Something was drawn: not the cleared texture.
    float alpha = 0;
    for (std::size_t p = 3; p < drawn.rgba.size(); p += 4)
        alpha += drawn.rgba[p];
    EXPECT_GT(alpha, 0.05f * kW * kH);
}

TEST(GlRayCasterInContext, TheCoarsePassInterpolatesAsOffscreen)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture();
    s.draw(frame, ARBOR_RENDER_PASS_COARSE);
    const RenderedImage drawn = HostContext::read(frame);
    const double own = test::psnr(drawn, s.render(s.gl, {ARBOR_RENDER_PASS_COARSE}, kW, kH));
    EXPECT_GT(own, 80.0) << own << " dB from the plugin's offscreen coarse image";
    EXPECT_LT(test::psnr(drawn, s.render(s.gl, {}, kW, kH)), 80.0) << "the coarse pass drew the full one";
}

TEST(GlRayCasterInContext, SupersamplePassesBlendIntoTheTexture)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture();
    s.draw(frame, ARBOR_RENDER_PASS_FULL);
    const RenderedImage first = HostContext::read(frame);
    RenderedImage offscreen = s.render(s.gl, {}, kW, kH);
    for (uint32_t n = 1; n <= 3; ++n) {
        s.draw(frame, ARBOR_RENDER_PASS_SUPERSAMPLE, n);
        render_region(s.gl, s.request, offscreen, {}, {ARBOR_RENDER_PASS_SUPERSAMPLE, n, s.tf_revision});
    }
    const RenderedImage refined = HostContext::read(frame);
    EXPECT_LT(test::psnr(refined, first), 90.0) << "supersampling changed nothing";
    const double own = test::psnr(refined, offscreen);
    EXPECT_GT(own, 80.0) << own << " dB from the offscreen refinement";
}

TEST(GlRayCasterInContext, ATileWritesItsRegionOnly)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture(GL_RGBA32F, 0.25f);
    const Region tile{37, 20, 64, 50};
    s.draw(frame, ARBOR_RENDER_PASS_FULL, 0, tile);
    const RenderedImage drawn = HostContext::read(frame);
    const RenderedImage whole = s.render(s.gl, {}, kW, kH);
    double se = 0;
    std::size_t outside_changed = 0;
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x)
            for (int c = 0; c < 4; ++c) {
                const std::size_t i = (std::size_t{y} * kW + x) * 4 + static_cast<std::size_t>(c);
                const bool inside = x >= tile.x && x < tile.x + tile.width && y >= tile.y && y < tile.y + tile.height;
                if (inside)
                    se += (drawn.rgba[i] - whole.rgba[i]) * (drawn.rgba[i] - whole.rgba[i]);
                else
                    outside_changed += drawn.rgba[i] != 0.25f;
            }
    EXPECT_EQ(outside_changed, 0u) << "texels outside the tile were written";
    EXPECT_LT(se / (4.0 * tile.width * tile.height), 1e-8) << "the tile differs from the whole frame there";
}

TEST(GlRayCasterInContext, AnEightBitTextureHoldsTheImageToItsPrecision)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture(GL_RGBA8);
    s.draw(frame, ARBOR_RENDER_PASS_FULL);
    const double db = test::psnr(HostContext::read(frame), s.render(s.gl, {}, kW, kH));
    // Rounding to 1/255 alone is about 59 dB.
    EXPECT_GT(db, 50.0) << db << " dB";
}

// Cancels its task at the first progress report.
struct CancelAtOnce : ProgressSink {
    void report(const std::string &, double) override { source.request_stop(); }
    void finish() override {}
    std::stop_source source;
};

TEST(GlRayCasterInContext, ACancelledPassLeavesTheTextureAndTheNextOneDraws)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture(GL_RGBA32F, 0.5f);
    CancelAtOnce sink;
    EXPECT_THROW(s.draw(frame, ARBOR_RENDER_PASS_FULL, 0, {}, &sink, sink.source.get_token()), Cancelled);
    for (float x : HostContext::read(frame).rgba)
        ASSERT_EQ(x, 0.5f);
    s.draw(frame, ARBOR_RENDER_PASS_FULL);
    EXPECT_GT(test::psnr(HostContext::read(frame), s.render(s.gl, {}, kW, kH)), 80.0);
}

TEST(GlRayCasterInContext, AfterReleaseItMakesItsObjectsAnew)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture();
    s.draw(frame, ARBOR_RENDER_PASS_FULL);
    release_gl(s.gl);
    const GlFrame again = s.context.texture(GL_RGBA32F, 0.5f);
    s.draw(again, ARBOR_RENDER_PASS_FULL);
    EXPECT_GT(test::psnr(HostContext::read(again), HostContext::read(frame)), 80.0);
}

TEST(GlRayCasterInContext, ATargetOfTheWrongSizeIsRefused)
{
    InContext s;
    REQUIRE_CONTEXT(s);
    const GlFrame frame = s.context.texture();
    arbor_render_request_v2 r{};
    r.struct_size = sizeof r;
    r.pass = ARBOR_RENDER_PASS_FULL;
    r.volume = s.request.volume;
    r.labels = s.request.labels;
    r.transfer_functions = s.request.transfer_functions;
    r.camera = s.request.camera;
    r.frame_width = kW + 1;
    r.frame_height = kH;
    r.region_width = kW + 1;
    r.region_height = kH;
    arbor_gl_target target{};
    target.struct_size = sizeof target;
    target.texture = frame.texture;
    target.width = kW;
    target.height = kH;
    const auto &table = s.gl.interface<arbor_renderer_gl_v1>(ARBOR_INTERFACE_RENDERER_GL);
    Task task;
    EXPECT_EQ(table.render_gl(s.gl.get(), &r, &target, task.get()), ARBOR_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(s.gl.last_error().find("frame's size"), std::string::npos) << s.gl.last_error();
}

// The workstation's path: a progressive view with a surface.  When the
// OpenGL ray caster cannot draw into it (here a canvas that names no
// texture), the view says why once and falls back to images, without an
// error and without asking again.
TEST(GlRayCasterInContext, AViewFallsBackToImagesWhenTheRendererCannotDrawIntoItsSurface)
{
    using namespace std::chrono_literals;
    pipeline::Pipeline p(test::built_plugins());
    pipeline::Document d = pipeline::default_document();
    d.input.phantom = pipeline::PhantomInput{};
    d.input.phantom->size = 48;
    d.cut.keep = 6;
    d.view.width = d.view.height = 64;
    d.view.renderer.id = kGl;
    p.set_document(d);
    const auto surface = std::make_shared<test::CountingSurface>();
    pipeline::ProgressiveView::Options options{50ms, 1};
    options.surface = surface;
    pipeline::ProgressiveView view(p, options);
    const uint64_t t = view.touch();
    const auto refined = view.wait_for(t, ARBOR_RENDER_PASS_SUPERSAMPLE, 1, 120s);
    ASSERT_TRUE(refined) << view.error();
    EXPECT_FALSE(refined->gpu);
    EXPECT_EQ(refined->image.width, 64u);
    EXPECT_TRUE(view.error().empty()) << view.error();
    EXPECT_EQ(surface->canvases, 1) << "asked again after it failed";
    EXPECT_EQ(surface->snapshots, 0);
}

} // namespace
} // namespace arbor
