// The pipeline: every kind of change re-runs exactly the stages that depend
// on it (stage-run counters), jobs cancel one at a time, a newer request
// supersedes an older one, results are snapshots, errors name their cause,
// and the on-disk tree cache is consulted.  Real plugins, built-in phantom.
#include "pipeline/pipeline.hpp"
#include "pipeline/tree_cache.hpp"

#include "plugin_fixture.hpp"
#include "test_paths.hpp"

#include "core/cancelled.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

namespace arbor::pipeline {
namespace {

using namespace std::chrono_literals;

Document phantom_document(int64_t size = 40, double noise = 4.0)
{
    Document d = default_document();
    d.input.phantom = PhantomInput{};
    d.input.phantom->size = size;
    d.input.phantom->noise = noise;
    d.cut.keep = 8;
    d.auto_denoise = false; // keep the noise's branches: the tests select among them
    d.view.width = d.view.height = 48;
    return d;
}

// Stage-run counters as a map, for readable failures.
std::map<std::string, uint64_t> runs(const Pipeline &p)
{
    std::map<std::string, uint64_t> out;
    const auto r = p.stage_runs();
    for (std::size_t s = 0; s < kStageCount; ++s)
        out[stage_name(static_cast<Stage>(s))] = r[s];
    return out;
}

// The counters after one change, minus those before: 1 where it re-ran.
std::map<std::string, uint64_t> reruns(const std::map<std::string, uint64_t> &before, const Pipeline &p)
{
    std::map<std::string, uint64_t> out = runs(p);
    for (auto &[stage, n] : out)
        n -= before.at(stage);
    return out;
}

std::map<std::string, uint64_t> only(std::initializer_list<const char *> stages)
{
    std::map<std::string, uint64_t> out;
    for (std::size_t s = 0; s < kStageCount; ++s)
        out[stage_name(static_cast<Stage>(s))] = 0;
    for (const char *s : stages)
        out.at(s) = 1;
    return out;
}

const std::map<std::string, uint64_t> kLook = only({"depiction", "transfer_functions", "render"});

class PipelineStages : public ::testing::Test {
protected:
    PipelineStages() : pipeline(test::built_plugins())
    {
        pipeline.set_document(phantom_document());
        first = pipeline.run<Stage::Render>();
        base = runs(pipeline);
    }

    // Applies `change` to the document, asks for `target` again (the
    // render), returns what re-ran.
    template <class F> std::map<std::string, uint64_t> after(F change, Stage target = Stage::Render)
    {
        Document d = pipeline.document();
        change(d);
        pipeline.set_document(d);
        pipeline.request(target)->wait();
        auto out = reruns(base, pipeline);
        base = runs(pipeline);
        return out;
    }

    Pipeline pipeline;
    std::shared_ptr<const RenderResult> first;
    std::map<std::string, uint64_t> base;
};

TEST_F(PipelineStages, FirstRenderRunsEveryStageOnceAndTheLegendNotAtAll)
{
    auto want = only({"import", "filter", "contour_tree", "decomposition", "cut", "labels", "depiction",
                      "transfer_functions", "render"});
    EXPECT_EQ(base, want);
    EXPECT_EQ(first->image.width, 48u);
    for (std::size_t s = 0; s < kStageCount; ++s)
        EXPECT_EQ(pipeline.is_current(static_cast<Stage>(s)), static_cast<Stage>(s) != Stage::Legend);
}

TEST_F(PipelineStages, NothingChangedNothingRuns)
{
    EXPECT_EQ(after([](Document &) {}), only({}));
    // Setting the same values again (as a front does on every frame) is no change either.
    // The same plugin by its short name with its defaults left out resolves to
    // the same full setting.
    EXPECT_EQ(after([](Document &d) {
                  d.appearance.generator = {"residue-flow", "", {}};
                  d.simplifier = {"org.arbor.simplifier.itri", "", {}};
              }),
              only({}));
}

TEST_F(PipelineStages, GeneratorAndDepictorParametersAndSelectionRedoTheLook)
{
    EXPECT_EQ(after([](Document &d) { d.appearance.generator.params["flow-rate"] = "120"; }), kLook);
    EXPECT_EQ(after([](Document &d) { d.appearance.generator.params["shape"] = "hat"; }), kLook);
    EXPECT_EQ(after([](Document &d) { d.appearance.generator.params["hues"] = "X:30"; }), kLook);
    EXPECT_EQ(after([](Document &d) { d.appearance.depictor.params["floor"] = "0.3"; }), kLook);
    EXPECT_EQ(after([](Document &d) { d.appearance.selected = 2; }), kLook);
    EXPECT_EQ(after([](Document &d) { d.appearance.depictor = {}; }), kLook); // relation none
    EXPECT_EQ(after([](Document &d) { d.appearance.generator = {"histogram-ramp", "", {}}; }), kLook);
}

TEST_F(PipelineStages, KeepAndThresholdRedoTheCutNeverTheDecomposition)
{
    const auto want = only({"cut", "labels", "depiction", "transfer_functions", "render"});
    EXPECT_EQ(after([](Document &d) { d.cut.keep = 5; }), want);
    EXPECT_EQ(after([](Document &d) {
                  d.cut.keep.reset();
                  d.cut.threshold = 0.001;
              }),
              want);
    EXPECT_EQ(after([](Document &d) { d.cut = {}; }), want); // the knee
    EXPECT_TRUE(pipeline.latest<Stage::Cut>()->knee);
}

TEST_F(PipelineStages, SimplifierOrItsParametersRedoTheDecompositionNeverTheTree)
{
    const auto want = only({"decomposition", "cut", "labels", "depiction", "transfer_functions", "render"});
    EXPECT_EQ(after([](Document &d) { d.simplifier = {"persistence", "", {}}; }), want);
    EXPECT_EQ(after([](Document &d) { d.simplifier = {"n-measure", "", {}}; }), want);
    EXPECT_EQ(after([](Document &d) { d.simplifier.params["measures"] = "persistence,volume"; }), want);
    EXPECT_EQ(pipeline.latest<Stage::Decomposition>()->simplifier.id, "org.arbor.simplifier.n-measure");
}

TEST_F(PipelineStages, FilterRedoesTheTreeNeverTheImport)
{
    const auto want = only({"filter", "contour_tree", "decomposition", "cut", "labels", "depiction",
                            "transfer_functions", "render"});
    EXPECT_EQ(after([](Document &d) { d.filters = {{"gaussian", "", {{"sigma", "2"}}}}; }), want);
    EXPECT_EQ(after([](Document &d) { d.filters[0].params["sigma"] = "3"; }), want);
    EXPECT_EQ(after([](Document &d) { d.filters.push_back({"median", "", {}}); }), want);
    EXPECT_EQ(pipeline.latest<Stage::Filter>()->filters.size(), 2u);
}

TEST_F(PipelineStages, CameraImageSizeAndRendererParametersRedoTheRenderOnly)
{
    const auto want = only({"render"});
    EXPECT_EQ(after([](Document &d) { d.view.orbit.azimuth = 40; }), want);
    EXPECT_EQ(after([](Document &d) { d.view.orbit.zoom = 1.5; }), want);
    EXPECT_EQ(after([](Document &d) { d.view.width = 64; }), want);
    EXPECT_EQ(after([](Document &d) { d.view.background = {1, 1, 1, 1}; }), want);
    EXPECT_EQ(after([](Document &d) { d.view.renderer.params["shading"] = "false"; }), want);
    EXPECT_EQ(pipeline.latest<Stage::Render>()->image.width, 64u);
}

TEST_F(PipelineStages, InputRedoesEverything)
{
    auto want = only({"import", "filter", "contour_tree", "decomposition", "cut", "labels", "depiction",
                      "transfer_functions", "render"});
    EXPECT_EQ(after([](Document &d) { d.input.phantom->seed = 2; }), want);
}

TEST_F(PipelineStages, TheLegendFollowsTheCutAndTheLookOnly)
{
    pipeline.run<Stage::Legend>();
    base = runs(pipeline);
    EXPECT_EQ(after([](Document &d) { d.view.orbit.azimuth = 90; }, Stage::Legend), only({}));
    EXPECT_EQ(after([](Document &d) { d.appearance.selected = 1; }, Stage::Legend), only({"legend"}));
    EXPECT_EQ(after([](Document &d) { d.cut.keep = 6; }, Stage::Legend), only({"cut", "legend"}));
    const auto legend = pipeline.latest<Stage::Legend>();
    EXPECT_EQ(legend->selected, 1u);
    EXPECT_EQ(legend->rgba.size(), std::size_t{512} * 512 * 4);
}

TEST_F(PipelineStages, ResultsAreSnapshotsThatOutliveTheirSuccessors)
{
    const RenderedImage copy = first->image;
    after([](Document &d) { d.view.orbit.azimuth = 120; });
    after([](Document &d) { d.input.phantom->seed = 3; });
    EXPECT_EQ(first->image.rgba, copy.rgba); // still whole, untouched
    EXPECT_NE(pipeline.latest<Stage::Render>()->image.rgba, copy.rgba);
}

// Waits (a while) for the last holder of a result to let it go: a job's
// worker lets go of its job as it exits, which may come a moment after the
// stage downstream is done.
template <class T> bool expires(const std::weak_ptr<T> &held)
{
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!held.expired() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return held.expired();
}

// single_pass (`arbor run`): the input's voxels go once a filter made its
// own, and come back by importing again when they are needed.
TEST(Pipeline, ReleasedImportedVoxelsAreFreedAfterTheFilterAndImportedAgainWhenNeeded)
{
    PipelineOptions options;
    options.single_pass = true;
    Pipeline p(test::built_plugins(), options);
    Document d = phantom_document();
    d.filters = {{"gaussian", "", {{"sigma", "1"}}}};
    p.set_document(d);
    std::weak_ptr<const Volume> imported = p.run<Stage::Import>()->volume;
    const auto filtered = p.run<Stage::Filter>();
    ASSERT_NE(filtered->volume.get(), nullptr);
    EXPECT_TRUE(expires(imported)) << "the imported voxels are still held";
    EXPECT_FALSE(p.is_current(Stage::Import));
    EXPECT_TRUE(p.is_current(Stage::Filter));

    // The rest of the run does not need them.
    p.run<Stage::Render>();
    EXPECT_EQ(runs(p).at("import"), 1u);

    // Another filter reads the input again: imported a second time, and the
    // result is the one a pipeline that kept the voxels computes.
    d.filters[0].params["sigma"] = "2";
    p.set_document(d);
    const auto refiltered = p.run<Stage::Filter>();
    EXPECT_EQ(runs(p).at("import"), 2u);
    Pipeline keeping(test::built_plugins());
    keeping.set_document(d);
    const auto reference = keeping.run<Stage::Filter>();
    ASSERT_EQ(refiltered->volume->byte_size(), reference->volume->byte_size());
    EXPECT_EQ(std::memcmp(refiltered->volume->data(), reference->volume->data(), reference->volume->byte_size()), 0);
    EXPECT_NE(keeping.latest<Stage::Import>(), nullptr); // by default the import stays

    // An empty chain passes the import's own voxels on: nothing to release.
    d.filters.clear();
    p.set_document(d);
    p.run<Stage::Filter>();
    EXPECT_TRUE(p.is_current(Stage::Import));
}

// single_pass, the whole pass of `arbor run`: the imported voxels go after
// the filter and the contour tree's segmentation (vertex_arc) after the cut
// of the declared last document, before the render; the image is the one a
// pipeline that keeps every result (the workstation's) renders, and no stage
// runs twice.  That pipeline lets nothing go.
TEST(Pipeline, ASinglePassLetsTheInputAndTheSegmentationGoAndTheNormalModeKeepsThem)
{
    Document d = phantom_document();
    d.filters = {{"gaussian", "", {{"sigma", "1"}}}};
    const std::size_t voxels = std::size_t{40} * 40 * 40;

    Pipeline keeping(test::built_plugins());
    keeping.set_document(d);
    EXPECT_THROW(keeping.declare_last_document(), std::logic_error);
    const auto reference = keeping.run<Stage::Render>();
    const auto whole = keeping.latest<Stage::ContourTree>();
    for (std::size_t s = 0; s < kStageCount; ++s)
        EXPECT_EQ(keeping.is_current(static_cast<Stage>(s)), static_cast<Stage>(s) != Stage::Legend);
    EXPECT_NE(keeping.latest<Stage::Import>()->volume, nullptr);
    EXPECT_EQ(whole->tree.vertex_arc.size(), voxels);

    PipelineOptions options;
    options.single_pass = true;
    Pipeline p(test::built_plugins(), options);
    p.set_document(d);
    p.declare_last_document();
    const std::weak_ptr<const Volume> imported = p.run<Stage::Import>()->volume;
    const std::weak_ptr<const ContourTreeResult> tree = p.run<Stage::ContourTree>();
    EXPECT_TRUE(expires(imported)) << "the imported voxels are still held";
    ASSERT_FALSE(tree.expired());
    EXPECT_EQ(tree.lock()->tree.vertex_arc.size(), voxels); // kept until the cut is made

    const auto image = p.run<Stage::Render>();
    EXPECT_TRUE(expires(tree)) << "the tree with its segmentation is still held";
    const auto kept = p.latest<Stage::ContourTree>();
    ASSERT_NE(kept, nullptr);
    EXPECT_TRUE(kept->tree.vertex_arc.empty());
    EXPECT_EQ(kept->tree.node_count(), whole->tree.node_count()); // what the report reads is left
    EXPECT_EQ(kept->tree.arc_count(), whole->tree.arc_count());
    EXPECT_EQ(kept->tree.node_vertex, whole->tree.node_vertex);
    EXPECT_EQ(kept->memory_plan, whole->memory_plan);
    EXPECT_FALSE(p.is_current(Stage::Import));
    EXPECT_FALSE(p.is_current(Stage::ContourTree));
    for (const Stage s : {Stage::Filter, Stage::Decomposition, Stage::Cut, Stage::Labels, Stage::Render})
        EXPECT_TRUE(p.is_current(s)) << stage_name(s);
    EXPECT_EQ(image->image.rgba, reference->image.rgba);
    EXPECT_EQ(p.run<Stage::Labels>()->labels, keeping.run<Stage::Labels>()->labels);
    EXPECT_EQ(runs(p), runs(keeping)); // nothing computed twice
}

// A single-pass sweep (`arbor run --keep 8,6 --shape ramp,hat`): every
// point's cut reads the one tree, so the segmentation stays until the last
// point - and goes at once when the last point's cut was made at an earlier
// point.  A cut asked for after the pass computes the tree again.
TEST(Pipeline, ASinglePassSweepKeepsTheSegmentationUntilTheLastDocumentsCut)
{
    PipelineOptions options;
    options.single_pass = true;
    Pipeline p(test::built_plugins(), options);
    Document d = phantom_document();
    const std::size_t voxels = std::size_t{40} * 40 * 40;
    p.set_document(d);
    p.run<Stage::Render>();
    d.cut.keep = 6;
    p.set_document(d);
    p.run<Stage::Render>();
    EXPECT_TRUE(p.is_current(Stage::ContourTree));
    EXPECT_EQ(p.latest<Stage::ContourTree>()->tree.vertex_arc.size(), voxels);

    // The last point: the same cut, another look.
    d.appearance.generator.params["shape"] = "hat";
    p.set_document(d);
    p.declare_last_document();
    EXPECT_FALSE(p.is_current(Stage::ContourTree));
    EXPECT_TRUE(p.latest<Stage::ContourTree>()->tree.vertex_arc.empty());
    p.run<Stage::Render>();
    auto r = runs(p);
    EXPECT_EQ(r.at("contour_tree"), 1u);
    EXPECT_EQ(r.at("cut"), 2u);
    EXPECT_EQ(r.at("render"), 3u);

    // Another document takes the declaration back: its cut computes the
    // tree again, and keeps it.
    d.cut.keep = 5;
    p.set_document(d);
    const auto labels = p.run<Stage::Labels>();
    EXPECT_EQ(runs(p).at("contour_tree"), 2u);
    EXPECT_TRUE(p.is_current(Stage::ContourTree));
    EXPECT_EQ(p.latest<Stage::ContourTree>()->tree.vertex_arc.size(), voxels);
    Pipeline keeping(test::built_plugins());
    keeping.set_document(d);
    EXPECT_EQ(labels->labels, keeping.run<Stage::Labels>()->labels);
}

TEST(Pipeline, BadChoicesAreRefusedAndLeaveTheDocumentAsItWas)
{
    Pipeline p(test::built_plugins());
    const Document good = phantom_document();
    p.set_document(good);
    const Document resolved = p.document();
    const auto revisions = p.revisions();
    const auto refused = [&](auto change, const char *words) {
        Document d = good;
        change(d);
        try {
            p.set_document(d);
            ADD_FAILURE() << "accepted: " << words;
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
        EXPECT_EQ(p.document(), resolved);
        EXPECT_EQ(p.revisions(), revisions);
    };
    refused([](Document &d) { d.simplifier.id = "no-such-simplifier"; }, "no simplifier 'no-such-simplifier'");
    refused([](Document &d) { d.appearance.generator.params["flow-rate"] = "-5"; }, "flow-rate");
    refused([](Document &d) { d.appearance.generator.params["shape"] = "spiral"; }, "spiral");
    refused([](Document &d) { d.appearance.generator.params["no-such"] = "1"; }, "has no parameter 'no-such'");
    refused([](Document &d) { d.filters = {{"gaussian", "", {{"sigma", "lots"}}}}; }, "lots");
    refused([](Document &d) { d.view.renderer = {}; }, "no renderer");
    try {
        Document d = good;
        d.appearance.generator.params["flow-rate"] = "-5";
        p.set_document(d);
    } catch (const SettingError &e) {
        EXPECT_EQ(e.plugin_id, "org.arbor.tf.residue-flow");
        EXPECT_EQ(e.param_id, "flow-rate");
    }
}

TEST(Pipeline, ResolvedSettingsCarryTheFullIdTheVersionAndEveryParameter)
{
    Pipeline p(test::built_plugins());
    Document d = phantom_document();
    d.appearance.generator.params = {{"flow-rate", "30"}};
    p.set_document(d);
    const PluginSetting g = p.document().appearance.generator;
    EXPECT_EQ(g.id, "org.arbor.tf.residue-flow");
    EXPECT_FALSE(g.version.empty());
    EXPECT_EQ(g.params.at("flow-rate"), "30");
    EXPECT_EQ(g.params.at("shape"), "auto"); // a default, written out
    EXPECT_GE(g.params.size(), 10u);
}

TEST(Pipeline, AnErrorUpstreamIsTheErrorOfEveryStageDownstream)
{
    Pipeline p(test::built_plugins());
    Document d = phantom_document();
    d.input.phantom.reset();
    d.input.path = test::scratch_dir() / "nothing-here.nrrd";
    p.set_document(d);
    const std::shared_ptr<Job> job = p.request(Stage::Render);
    EXPECT_THROW(job->wait(), std::exception);
    EXPECT_EQ(job->state(), JobState::Failed);
    EXPECT_NE(job->error().find("nothing-here.nrrd"), std::string::npos) << job->error();
    EXPECT_FALSE(p.is_current(Stage::Import));
}

TEST(Pipeline, ASelectionOutsideTheTreeIsRefusedByName)
{
    Pipeline p(test::built_plugins());
    Document d = phantom_document();
    d.appearance.selected = 40;
    p.set_document(d);
    try {
        p.run<Stage::Render>();
        ADD_FAILURE() << "rendered";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("selected branch 40"), std::string::npos) << e.what();
    }
}

TEST(Pipeline, RequestsForTheSameInputsShareOneJob)
{
    Pipeline p(test::built_plugins());
    p.set_document(phantom_document(64, 6));
    const std::shared_ptr<Job> a = p.request(Stage::ContourTree);
    const std::shared_ptr<Job> b = p.request(Stage::ContourTree);
    EXPECT_EQ(a, b);
    b->wait();
    EXPECT_EQ(p.stage_runs()[index_of(Stage::ContourTree)], 1u);
    // Once finished, it is served from the stage's result.
    const std::shared_ptr<Job> c = p.request(Stage::ContourTree);
    EXPECT_EQ(c->state(), JobState::Done);
    EXPECT_EQ(c->wait(), b->wait());
}

// Waits until `job` runs (not merely waits for its upstream).
void wait_running(const Job &job)
{
    for (int i = 0; i < 4000 && job.state() == JobState::Waiting; ++i)
        std::this_thread::sleep_for(5ms);
    ASSERT_EQ(job.state(), JobState::Running);
}

// The built plugins plus org.arbor.test.gate, a filter that runs until it is
// cancelled: a job sure to be running while the test does something else.
const PluginRegistry &plugins_with_gate()
{
    static const std::unique_ptr<PluginRegistry> registry = [] {
        auto r = std::make_unique<PluginRegistry>();
        r->load_directories({test::plugin_dir(), std::filesystem::path(ARBOR_FIXTURE_PLUGIN_DIR) / "fixture-gate"});
        return r;
    }();
    return *registry;
}

const PluginSetting kGate{"org.arbor.test.gate", "", {}};

// Cancels `job` and checks it ends promptly as cancelled.
void cancel_and_expect_cancelled(Job &job)
{
    const auto at = std::chrono::steady_clock::now();
    job.cancel();
    EXPECT_THROW(job.wait(), Cancelled);
    EXPECT_EQ(job.state(), JobState::Cancelled);
    EXPECT_LT(std::chrono::steady_clock::now() - at, 2s) << stage_name(job.stage()) << " did not see the stop request";
}

TEST(PipelineJobs, CancellingOneJobLeavesTheOthersRunning)
{
    Pipeline p(plugins_with_gate());
    const Document d = phantom_document(40, 4);
    p.set_document(d);
    p.run<Stage::TransferFunctions>();
    p.run<Stage::Labels>();
    const std::shared_ptr<Job> render = p.request(Stage::Render);

    // Meanwhile the user tries a filter (one that runs until cancelled): its
    // job runs beside the render, and the tree job waits for it.
    Document filtered = d;
    filtered.filters = {kGate};
    p.set_document(filtered);
    const std::shared_ptr<Job> tree = p.request(Stage::ContourTree);
    std::shared_ptr<Job> gate;
    for (const std::shared_ptr<Job> &j : p.active_jobs())
        if (j->stage() == Stage::Filter)
            gate = j;
    ASSERT_TRUE(gate);
    wait_running(*gate);

    // The render finishes while the filter runs, with the image of the
    // document it was asked for.
    const auto image = std::static_pointer_cast<const RenderResult>(render->wait());
    EXPECT_EQ(render->state(), JobState::Done);
    EXPECT_EQ(gate->state(), JobState::Running);
    Pipeline fresh(test::built_plugins());
    fresh.set_document(d);
    EXPECT_EQ(fresh.run<Stage::Render>()->image.rgba, image->image.rgba);

    // Cancelling the tree job leaves the filter job it waits for running.
    cancel_and_expect_cancelled(*tree);
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(gate->state(), JobState::Running);
    cancel_and_expect_cancelled(*gate);
    EXPECT_EQ(p.stage_runs()[index_of(Stage::ContourTree)], 1u);
}

TEST(PipelineJobs, CancellingADownstreamJobLeavesItsUpstreamRunning)
{
    Pipeline p(plugins_with_gate());
    Document d = phantom_document(24, 2);
    d.filters = {kGate};
    p.set_document(d);
    const std::shared_ptr<Job> render = p.request(Stage::Render);
    const std::shared_ptr<Job> gate = p.request(Stage::Filter); // the running one, joined
    wait_running(*gate);
    EXPECT_EQ(render->state(), JobState::Waiting);
    cancel_and_expect_cancelled(*render);
    EXPECT_EQ(gate->state(), JobState::Running);
    cancel_and_expect_cancelled(*gate);
}

TEST(PipelineJobs, ANewerRequestForAStageCancelsTheOlderOne)
{
    Pipeline p(plugins_with_gate());
    Document d = phantom_document(24, 2);
    d.filters = {kGate};
    p.set_document(d);
    const std::shared_ptr<Job> older_tree = p.request(Stage::ContourTree);
    const std::shared_ptr<Job> older_gate = p.request(Stage::Filter);
    wait_running(*older_gate);
    d.filters = {kGate, kGate};
    p.set_document(d);
    const std::shared_ptr<Job> newer_tree = p.request(Stage::ContourTree);
    EXPECT_NE(newer_tree, older_tree);
    EXPECT_THROW(older_tree->wait(), Cancelled);
    EXPECT_THROW(older_gate->wait(), Cancelled);
    const std::shared_ptr<Job> newer_gate = p.request(Stage::Filter);
    EXPECT_NE(newer_gate, older_gate);
    wait_running(*newer_gate); // it had to wait for the older one to let go of the filter instance
    EXPECT_EQ(newer_tree->state(), JobState::Waiting);
    // The user goes back to no filter: the newest request wins again.
    d.filters.clear();
    p.set_document(d);
    EXPECT_EQ(p.run<Stage::ContourTree>()->tree.vertex_arc.size(), std::size_t{24} * 24 * 24);
    EXPECT_THROW(newer_tree->wait(), Cancelled);
    EXPECT_THROW(newer_gate->wait(), Cancelled);
    EXPECT_TRUE(p.is_current(Stage::ContourTree));
}

TEST(PipelineJobs, ANewerRenderSupersedesTheOlderAndIsTheLatest)
{
    Pipeline p(test::built_plugins());
    Document d = phantom_document(40, 4);
    p.set_document(d);
    const std::shared_ptr<Job> older = p.request(Stage::Render);
    d.view.orbit.azimuth = 45;
    d.view.width = 64;
    p.set_document(d);
    const std::shared_ptr<Job> newer = p.request(Stage::Render);
    newer->wait();
    older->wait_for(10s);
    // Whether the older one was cancelled or had finished, the newer is the latest.
    EXPECT_TRUE(older->state() == JobState::Cancelled || older->state() == JobState::Done);
    EXPECT_EQ(p.latest<Stage::Render>()->image.width, 64u);
    EXPECT_TRUE(p.is_current(Stage::Render));
}

TEST(PipelineJobs, CancelAllStopsEveryJobAndTheNextRequestStartsAfresh)
{
    Pipeline p(plugins_with_gate());
    Document d = phantom_document(24, 2);
    d.filters = {kGate};
    p.set_document(d);
    const std::shared_ptr<Job> render = p.request(Stage::Render);
    wait_running(*p.request(Stage::Filter));
    EXPECT_EQ(p.active_jobs().size(), 8u); // filter .. render
    p.cancel_all();
    EXPECT_THROW(render->wait(), Cancelled);
    for (int i = 0; i < 200 && !p.active_jobs().empty(); ++i)
        std::this_thread::sleep_for(5ms);
    EXPECT_TRUE(p.active_jobs().empty());
    d.filters.clear();
    p.set_document(d);
    EXPECT_EQ(p.run<Stage::Render>()->image.width, 48u);
}

TEST(PipelineJobs, DestroyingAPipelineCancelsItsJobs)
{
    std::shared_ptr<Job> gate;
    {
        Pipeline p(plugins_with_gate());
        Document d = phantom_document(24, 2);
        d.filters = {kGate};
        p.set_document(d);
        p.request(Stage::Render);
        gate = p.request(Stage::Filter);
        wait_running(*gate);
    } // would never return if the gate were not cancelled
    EXPECT_EQ(gate->state(), JobState::Cancelled);
}

// What a workstation does: its UI thread reads the newest finished results
// (and the jobs' progress) every frame while a worker keeps changing the
// view and rendering.  Under ThreadSanitizer any race in that hand-over fails.
TEST(Pipeline, AFrontReadsSnapshotsWhileJobsRun)
{
    Pipeline p(test::built_plugins());
    Document d = phantom_document(32, 3);
    p.set_document(d);
    p.run<Stage::Render>();
    std::atomic<bool> done{false};
    std::atomic<uint64_t> frames{0};
    std::thread ui([&] {
        while (!done) {
            if (const auto r = p.latest<Stage::Render>()) {
                float sum = 0;
                for (float x : r->image.rgba)
                    sum += x;
                EXPECT_GE(sum, 0.0f);
            }
            for (const std::shared_ptr<Job> &j : p.active_jobs())
                EXPECT_GE(j->fraction(), 0.0);
            p.is_current(Stage::Render);
            ++frames;
        }
    });
    for (int i = 0; i < 12; ++i) {
        d.view.orbit.azimuth = 30.0 * i;
        d.appearance.generator.params["flow-rate"] = std::to_string(20 * (i % 4));
        p.set_document(d);
        if (i % 3 == 2)
            p.run<Stage::Render>();
        else
            p.request(Stage::Render); // superseded by the next one, or finished
    }
    p.run<Stage::Render>();
    done = true;
    ui.join();
    EXPECT_GT(frames.load(), 0u);
    EXPECT_TRUE(p.is_current(Stage::Render));
}

TEST(Pipeline, JobsReportProgressAndKeepTheirLog)
{
    Pipeline p(test::built_plugins());
    p.set_document(phantom_document(64, 4));
    const std::shared_ptr<Job> tree = p.request(Stage::ContourTree);
    tree->wait();
    EXPECT_EQ(tree->fraction(), 1.0);
    EXPECT_FALSE(tree->activity().empty());
}

TEST(PipelineTreeCache, ASecondPipelineReadsTheTreeTheFirstComputed)
{
    PipelineOptions options;
    options.tree_cache_folder = test::scratch_dir() / "cache";
    const Document d = phantom_document(48, 5);
    std::shared_ptr<const ContourTreeResult> computed;
    {
        Pipeline p(test::built_plugins(), options);
        p.set_document(d);
        computed = p.run<Stage::ContourTree>();
        EXPECT_FALSE(computed->from_cache);
    }
    Pipeline p(test::built_plugins(), options);
    p.set_document(d);
    const auto read = p.run<Stage::ContourTree>();
    EXPECT_TRUE(read->from_cache);
    EXPECT_EQ(std::vector<uint32_t>(read->tree.node_vertex.begin(), read->tree.node_vertex.end()),
              std::vector<uint32_t>(computed->tree.node_vertex.begin(), computed->tree.node_vertex.end()));
    EXPECT_EQ(0, std::memcmp(read->tree.vertex_arc.data(), computed->tree.vertex_arc.data(),
                             computed->tree.vertex_arc.size() * sizeof(uint32_t)));
    // The same image from either tree.
    Pipeline q(test::built_plugins());
    q.set_document(d);
    EXPECT_EQ(p.run<Stage::Render>()->image.rgba, q.run<Stage::Render>()->image.rgba);
}

TEST(PipelineTreeCache, ADamagedEntryIsRecomputedWithAWarning)
{
    PipelineOptions options;
    options.tree_cache_folder = test::scratch_dir() / "cache";
    const Document d = phantom_document(40, 5);
    {
        Pipeline p(test::built_plugins(), options);
        p.set_document(d);
        p.run<Stage::ContourTree>();
    }
    std::filesystem::path entry;
    for (const auto &e : std::filesystem::directory_iterator(options.tree_cache_folder))
        entry = e.path();
    ASSERT_FALSE(entry.empty());
    std::filesystem::resize_file(entry, std::filesystem::file_size(entry) / 2);

    Pipeline p(test::built_plugins(), options);
    p.set_document(d);
    const std::shared_ptr<Job> job = p.request(Stage::ContourTree);
    const auto r = std::static_pointer_cast<const ContourTreeResult>(job->wait());
    EXPECT_FALSE(r->from_cache);
    bool warned = false;
    for (const LogEntry &e : job->log())
        warned |= e.level == ARBOR_LOG_WARNING && e.message.find("computing the tree again") != std::string::npos;
    EXPECT_TRUE(warned);
    // ... and stored whole again.
    Pipeline again(test::built_plugins(), options);
    again.set_document(d);
    EXPECT_TRUE(again.run<Stage::ContourTree>()->from_cache);
}

} // namespace
} // namespace arbor::pipeline
