// The Workstation without a window, on the built-in phantom through the
// real plugins: what a person's actions do to the pipeline and the views'
// state, each checked against an independent answer (the pipeline run
// directly, the phantom's geometry).
#include "workstation/recovery.hpp"
#include "workstation/workstation.hpp"
#include "workstation_fixture.hpp"

#include "pipeline/session.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace arbor::workstation {
namespace {

using pipeline::Stage;

using test_support::phantom_workstation;
using test_support::wait_idle;

TEST(Workstation, OpensRendersAndUndoesEveryChange)
{
    auto ws = phantom_workstation();
    wait_idle(*ws);
    ASSERT_TRUE(ws->error().empty()) << ws->error();
    const auto first = ws->pipeline().latest<Stage::Render>();
    ASSERT_TRUE(first);
    EXPECT_EQ(first->image.width, 96u);
    const auto runs = ws->pipeline().stage_runs();
    const std::string q0 = ws->document().appearance.generator.params.at("flow-rate");
    // The flow rate re-runs the transfer functions and the render, never the tree.
    ws->set("flow-rate", "200");
    wait_idle(*ws);
    const auto second = ws->pipeline().latest<Stage::Render>();
    EXPECT_NE(second->image.rgba, first->image.rgba) << "a new flow rate changes the picture";
    const auto after = ws->pipeline().stage_runs();
    EXPECT_EQ(after[index_of(Stage::ContourTree)], runs[index_of(Stage::ContourTree)]);
    EXPECT_GT(after[index_of(Stage::TransferFunctions)], runs[index_of(Stage::TransferFunctions)]);
    // Undo: the earlier document and the earlier picture again.
    ASSERT_TRUE(ws->undo());
    wait_idle(*ws);
    EXPECT_EQ(ws->document().appearance.generator.params.at("flow-rate"), q0);
    EXPECT_EQ(ws->pipeline().latest<Stage::Render>()->image.rgba, first->image.rgba);
    ASSERT_TRUE(ws->redo());
    wait_idle(*ws);
    EXPECT_EQ(ws->pipeline().latest<Stage::Render>()->image.rgba, second->image.rgba);
    // A refused value changes nothing and says why.
    const pipeline::Document before = ws->document();
    EXPECT_THROW(ws->set("flow-rate", "-5"), std::invalid_argument);
    EXPECT_EQ(ws->document(), before);
}

TEST(Workstation, TheFlowRatePeelsTheOuterLayersAway)
{
    auto ws = phantom_workstation();
    wait_idle(*ws);
    const auto root_share = [&] {
        const auto &v = ws->pipeline().latest<Stage::Render>()->image.label_visibility;
        double total = 0;
        for (double x : v)
            total += x;
        return total > 0 ? v.at(0) / total : 0.0;
    };
    const double at_default = root_share();
    ASSERT_GT(at_default, 0.02);
    ws->set("flow-rate", "10");
    wait_idle(*ws);
    const double low = root_share();
    ws->set("flow-rate", "1000");
    wait_idle(*ws);
    const double high = root_share();
    // The balance chose the default picture and no longer undoes the slider
    // (flow_peel.hpp): lower Q brings the body back, higher Q peels it.
    EXPECT_GT(low, 1.5 * at_default);
    EXPECT_LT(high, 0.5 * at_default);
}

TEST(Workstation, SelectionThresholdAndCrosshair)
{
    auto ws = phantom_workstation();
    wait_idle(*ws);
    const auto cut = ws->pipeline().latest<Stage::Cut>();
    ASSERT_GE(cut->kept(), 2u);
    ws->select(1);
    EXPECT_EQ(ws->document().appearance.selected, std::optional<int32_t>(1));
    wait_idle(*ws);
    EXPECT_EQ(ws->pipeline().latest<Stage::Legend>()->selected, 1u) << "the legend follows the selection";
    ws->select(std::nullopt);
    EXPECT_FALSE(ws->document().appearance.selected);
    // The threshold at the top keeps the root alone; at the bottom every branch.
    ws->drag_threshold(1.0);
    wait_idle(*ws);
    const std::size_t top = ws->pipeline().latest<Stage::Cut>()->kept();
    ws->drag_threshold(0.0);
    wait_idle(*ws);
    const std::size_t bottom = ws->pipeline().latest<Stage::Cut>()->kept();
    EXPECT_LE(top, 2u);
    // At the bottom: at most the root and every branch of importance above 0
    // (a cut leaves out the background's basins and branches whose parent
    // it left out).
    const auto &branches = ws->pipeline().latest<Stage::Decomposition>()->branches.branches;
    std::size_t positive = 1;
    for (std::size_t b = 1; b < branches.size(); ++b)
        positive += branches[b].importance > 0;
    EXPECT_LE(bottom, positive);
    EXPECT_GT(bottom, 10 * top);
    // The crosshair starts in the middle and stays inside the grid.
    const auto dims = ws->pipeline().latest<Stage::Filter>()->volume->geometry().dims;
    EXPECT_EQ(ws->view().crosshair, (std::array<int64_t, 3>{dims[0] / 2, dims[1] / 2, dims[2] / 2}));
    ws->move_crosshair({-5, 1000, 3});
    EXPECT_EQ(ws->view().crosshair, (std::array<int64_t, 3>{0, dims[1] - 1, 3}));
}

TEST(Workstation, AHiddenBranchIsGoneFromThePictureThroughNewTransferFunctionsUntilReset)
{
    auto ws = phantom_workstation();
    ws->set("keep", "4");
    wait_idle(*ws);
    const auto share = [&](uint32_t label) {
        const auto &v = ws->pipeline().latest<Stage::Render>()->image.label_visibility;
        double total = 0;
        for (double x : v)
            total += x;
        return v.at(label) / total;
    };
    // The branch with the largest share but the root's.
    uint32_t shown = 1;
    for (uint32_t b = 2; b < 4; ++b)
        if (share(b) > share(shown))
            shown = b;
    ASSERT_GT(share(shown), 0.01);
    pipeline::BranchStyle hidden;
    hidden.visible = false;
    ws->set_branch_style(shown, hidden);
    wait_idle(*ws);
    EXPECT_EQ(share(shown), 0.0) << "a hidden branch contributes nothing";
    // A new flow rate regenerates the transfer functions: still hidden.
    ws->set("flow-rate", "120");
    wait_idle(*ws);
    EXPECT_EQ(share(shown), 0.0);
    EXPECT_FALSE(ws->branch_style(shown).visible);
    // Twice the optical depth of another branch raises its share.
    const uint32_t other = shown == 1 ? 2 : 1;
    const double before = share(other);
    pipeline::BranchStyle denser;
    denser.opacity = 3;
    ws->set_branch_style(other, denser);
    wait_idle(*ws);
    EXPECT_GT(share(other), before);
    ws->reset_branch_styles();
    wait_idle(*ws);
    EXPECT_GT(share(shown), 0.01);
    EXPECT_THROW(ws->set_branch_style(99, hidden), std::invalid_argument);
}

TEST(Workstation, PickingTheCentreOfTheViewHitsTheHeadsSurfaceInFront)
{
    auto ws = phantom_workstation();
    wait_idle(*ws);
    ws->move_crosshair({0, 0, 0});
    // From the front (anterior), the centre pixel's first opaque point lies on
    // the midline: i in the middle, j in the front half, k in the middle.
    ASSERT_TRUE(ws->pick(48, 48));
    const auto c = ws->view().crosshair;
    const auto dims = ws->pipeline().latest<Stage::Filter>()->volume->geometry().dims;
    EXPECT_NEAR(c[0], dims[0] / 2, 3);
    EXPECT_NEAR(c[2], dims[2] / 2, 3);
    EXPECT_LT(c[1], dims[1] / 2) << "the first opaque point is in front of the centre";
    EXPECT_FALSE(ws->pick(1, 1)) << "a corner ray hits nothing";
    // What was picked is selected, as a click on a slice selects.
    const auto labels = ws->pipeline().latest<Stage::Labels>();
    const uint32_t under = labels->labels[static_cast<std::size_t>(c[0] + dims[0] * (c[1] + dims[1] * c[2]))];
    if (under > 0)
        EXPECT_EQ(ws->document().appearance.selected, std::optional<int32_t>(static_cast<int32_t>(under)));
    else
        EXPECT_FALSE(ws->document().appearance.selected);
}

TEST(Workstation, SessionsRoundTripToTheSameDocument)
{
    auto ws = phantom_workstation();
    ws->set("keep", "4");
    ws->orbit(40, 15);
    wait_idle(*ws);
    pipeline::BranchStyle style;
    style.opacity = 0.5;
    style.color = std::array<double, 3>{0.2, 0.4, 0.9};
    ws->set_branch_style(2, style);
    wait_idle(*ws);
    const std::filesystem::path path = test::scratch_dir() / "workstation-session.json";
    ws->save_session(path);
    auto again = std::make_unique<Workstation>(test::built_plugins(), pipeline::PipelineOptions{});
    again->set_viewport(96, 96);
    again->open(path);
    wait_idle(*again);
    EXPECT_EQ(again->pipeline().document(), ws->pipeline().document());
    EXPECT_EQ(again->branch_style(2), style) << "branch styles are part of the session";
    EXPECT_EQ(again->pipeline().latest<Stage::Render>()->image.rgba, ws->pipeline().latest<Stage::Render>()->image.rgba);
    EXPECT_THROW(again->open(test::scratch_dir() / "no-such-file.nrrd"), std::invalid_argument);
}

TEST(Workstation, TheAutosaveKeepsTheLatestSessionAndANormalEndRemovesIt)
{
    auto ws = phantom_workstation();
    wait_idle(*ws);
    const std::filesystem::path path = test::scratch_dir() / "recovery" / "recovery.arbor-session.json";
    std::filesystem::remove(path);
    Autosave autosave(path);
    autosave.tick(*ws, 10.0);
    ASSERT_TRUE(std::filesystem::exists(path));
    const auto read = [&] { return pipeline::read_session(path, ws->catalog()).document; };
    EXPECT_EQ(read(), ws->pipeline().document());
    // At most every two seconds; then the newest choices.
    ws->set("keep", "3");
    autosave.tick(*ws, 11.0);
    EXPECT_NE(read().cut.keep, std::optional<std::size_t>(3));
    autosave.tick(*ws, 12.5);
    EXPECT_EQ(read().cut.keep, std::optional<std::size_t>(3));
    // What a restore opens: the same document.
    auto restored = std::make_unique<Workstation>(test::built_plugins(), pipeline::PipelineOptions{});
    restored->set_viewport(96, 96);
    restored->open(path);
    EXPECT_EQ(restored->pipeline().document(), ws->pipeline().document());
    autosave.finish();
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(Workstation, CancelStopsEveryJobUntilResume)
{
    auto ws = test_support::slow_phantom_workstation();
    // Cancel while the contour tree is computed.
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    bool computing = false;
    while (!computing && std::chrono::steady_clock::now() < end) {
        ws->poll();
        for (const auto &job : ws->jobs())
            computing = computing || (job->stage() == Stage::ContourTree && job->state() == pipeline::JobState::Running);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(computing);
    ws->cancel();
    wait_idle(*ws, 60);
    EXPECT_TRUE(ws->cancelled());
    EXPECT_TRUE(ws->jobs().empty());
    EXPECT_FALSE(ws->pipeline().is_current(Stage::ContourTree));
    // Nothing starts again by itself.
    for (int i = 0; i < 20; ++i) {
        ws->poll();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_TRUE(ws->jobs().empty());
    ws->resume();
    EXPECT_FALSE(ws->cancelled());
    wait_idle(*ws, 300);
    EXPECT_TRUE(ws->pipeline().is_current(Stage::Render));
}

TEST(Workstation, APreviewNeedsNoTopology)
{
    // What the 3D view shows while the contour tree is computed: the volume
    // from its values, rendered without the tree having run.
    pipeline::Pipeline p(test::built_plugins());
    pipeline::Document d = pipeline::default_document();
    d.input.phantom = pipeline::PhantomInput{"head", 64};
    d.view.renderer.id = "cpu-raycast";
    d.view.width = d.view.height = 64;
    p.set_document(d);
    RenderedImage frame;
    p.preview_pass(frame, {ARBOR_RENDER_PASS_FULL, 0, 0});
    EXPECT_EQ(p.stage_runs()[index_of(Stage::ContourTree)], 0u);
    EXPECT_EQ(frame.width, 64u);
    // The head lights the middle of the picture; the corners stay the black background.
    const auto brightness = [&](uint32_t x, uint32_t y) {
        const float *p = &frame.rgba[(std::size_t{y} * 64 + x) * 4];
        return p[0] + p[1] + p[2];
    };
    EXPECT_GT(brightness(32, 32), 0.3f);
    EXPECT_EQ(brightness(0, 0), 0.0f);
}

TEST(Workstation, TheFirstFrameOfANewScanIsAPreviewWhenTheTreeIsNotReady)
{
    // The preview waits for the filtered volume only; the tree of a noisy
    // 160^3 phantom takes seconds after that, the coarse preview milliseconds.
    auto ws = test_support::slow_phantom_workstation();
    std::shared_ptr<const pipeline::ProgressiveView::Frame> first;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!first && std::chrono::steady_clock::now() < end) {
        ws->poll();
        first = ws->volume_view().latest();
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ASSERT_TRUE(first);
    EXPECT_TRUE(first->preview) << "the first frame comes before the tree, from the values";
    wait_idle(*ws, 300);
    EXPECT_FALSE(ws->volume_view().latest()->preview) << "the topology's frame replaces it";
}

} // namespace
} // namespace arbor::workstation
