// The progressive view: a coarse frame at once after a touch, the
// pipeline's full render once the user is idle, supersampling after it;
// touches that come quickly keep it coarse, and a newer touch's answer is
// never replaced by an older one's.  Real plugins, built-in phantom.
#include "pipeline/progressive_view.hpp"

#include "counting_surface.hpp"
#include "plugin_fixture.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace arbor::pipeline {
namespace {

using namespace std::chrono_literals;

Document small_head()
{
    Document d = default_document();
    d.input.phantom = PhantomInput{};
    d.input.phantom->size = 48;
    d.cut.keep = 6;
    d.view.width = d.view.height = 64;
    return d;
}

TEST(ProgressiveView, CoarseAtOnceThenTheFullRenderThenSupersamples)
{
    Pipeline p(test::built_plugins());
    p.set_document(small_head());
    ProgressiveView view(p, {50ms, 2});
    const uint64_t t = view.touch();
    const auto coarse = view.wait_for(t, ARBOR_RENDER_PASS_COARSE, 0, 60s);
    ASSERT_TRUE(coarse) << view.error();
    EXPECT_EQ(coarse->touch, t);
    EXPECT_EQ(coarse->image.width, 64u);
    const auto full = view.wait_for(t, ARBOR_RENDER_PASS_FULL, 0, 60s);
    ASSERT_TRUE(full) << view.error();
    // The refined frame is the pipeline's render, pixel for pixel.
    const auto render = p.latest<Stage::Render>();
    ASSERT_TRUE(render);
    if (full->pass == ARBOR_RENDER_PASS_FULL) { // (it may have been refined further already)
        EXPECT_EQ(full->image.rgba, render->image.rgba);
    }
    const auto refined = view.wait_for(t, ARBOR_RENDER_PASS_SUPERSAMPLE, 2, 60s);
    ASSERT_TRUE(refined) << view.error();
    EXPECT_EQ(refined->pass, ARBOR_RENDER_PASS_SUPERSAMPLE);
    EXPECT_EQ(refined->samples, 2u);
    EXPECT_NE(refined->image.rgba, render->image.rgba);
    EXPECT_TRUE(view.error().empty());
}

TEST(ProgressiveView, TouchesInQuickSuccessionStayCoarseAndTheNewestWins)
{
    Pipeline p(test::built_plugins());
    Document d = small_head();
    p.set_document(d);
    ProgressiveView view(p, {400ms, 0});
    uint64_t t = view.touch();
    ASSERT_TRUE(view.wait_for(t, ARBOR_RENDER_PASS_COARSE, 0, 60s)) << view.error();
    const auto renders_before = p.stage_runs()[static_cast<std::size_t>(Stage::Render)];
    // An orbiting mouse: a touch every 40 ms, for a while.
    for (int i = 1; i <= 6; ++i) {
        d.view.orbit.azimuth = 10.0 * i;
        p.set_view(d.view);
        t = view.touch();
        std::this_thread::sleep_for(40ms);
    }
    const auto last_coarse = view.wait_for(t, ARBOR_RENDER_PASS_COARSE, 0, 60s);
    ASSERT_TRUE(last_coarse) << view.error();
    EXPECT_EQ(last_coarse->touch, t);
    // No full render happened while the touches came faster than the idle time.
    EXPECT_EQ(p.stage_runs()[static_cast<std::size_t>(Stage::Render)], renders_before);
    // Then quiet: the full render of the last view.
    const auto full = view.wait_for(t, ARBOR_RENDER_PASS_FULL, 0, 60s);
    ASSERT_TRUE(full) << view.error();
    EXPECT_EQ(full->touch, t);
    EXPECT_EQ(full->pass, ARBOR_RENDER_PASS_FULL);
    EXPECT_EQ(full->image.rgba, p.latest<Stage::Render>()->image.rgba);
    EXPECT_EQ(p.document().view.orbit.azimuth, 60.0);
    EXPECT_EQ(view.latest()->touch, t); // nothing older came after it
}

TEST(ProgressiveView, AnErrorIsReportedAndTheNextTouchTriesAgain)
{
    Pipeline p(test::built_plugins());
    ProgressiveView view(p, {20ms, 0});
    view.touch(); // no input yet
    for (int i = 0; i < 200 && view.error().empty(); ++i)
        std::this_thread::sleep_for(10ms);
    EXPECT_FALSE(view.error().empty());
    EXPECT_FALSE(view.latest());
    p.set_document(small_head());
    const uint64_t t = view.touch();
    ASSERT_TRUE(view.wait_for(t, ARBOR_RENDER_PASS_FULL, 0, 60s)) << view.error();
}

// With a surface but a renderer that draws no OpenGL (the CPU ray
// caster): images as without one, the surface's context made current on
// the view's thread once and let go when the view ends, its canvas never
// asked for.
TEST(ProgressiveView, ARendererThatDrawsNoOpenGlGivesImagesBesideASurface)
{
    Pipeline p(test::built_plugins());
    p.set_document(small_head());
    const auto surface = std::make_shared<test::CountingSurface>();
    {
        ProgressiveView::Options options{50ms, 1};
        options.surface = surface;
        ProgressiveView view(p, options);
        const uint64_t t = view.touch();
        const auto refined = view.wait_for(t, ARBOR_RENDER_PASS_SUPERSAMPLE, 1, 60s);
        ASSERT_TRUE(refined) << view.error();
        EXPECT_FALSE(refined->gpu);
        EXPECT_EQ(refined->image.width, 64u);
        EXPECT_TRUE(view.error().empty());
    }
    EXPECT_EQ(surface->made_current, 1);
    EXPECT_EQ(surface->released, 1);
    EXPECT_EQ(surface->canvases, 0);
    EXPECT_EQ(surface->snapshots, 0);
}

} // namespace
} // namespace arbor::pipeline
