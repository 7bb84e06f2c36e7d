// Plugin isolation (host/isolated_library.hpp): plugins in arbor-plugin-host
// give the same results as in-process, and a crash, abort, hang or runaway
// allocation fails the call with a message naming the plugin and the call,
// while this process carries on and the plugin comes back at its next call.
#include "global_ramp.hpp"
#include "plugin_fixture.hpp"
#include "topology_oracles.hpp"

#include "host/branch_tree_record.hpp"
#include "host/filter_run.hpp"
#include "host/rendering.hpp"
#include "host/tf_generation.hpp"
#include "host/volume_import.hpp"
#include "host/param_text.hpp"
#include "host/simplifier_importance.hpp"
#include "io/phantom.hpp"
#include "topology/branch_decomposition.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

namespace arbor {
namespace {

namespace fs = std::filesystem;

fs::path helper()
{
    return fs::read_symlink("/proc/self/exe").parent_path() / "arbor-plugin-host";
}

// Every library of `folder` isolated: a timeout of 2 s and a memory limit.
std::unique_ptr<PluginRegistry> isolated(const fs::path &folder, uint64_t memory_limit = uint64_t{1} << 30)
{
    auto r = std::make_unique<PluginRegistry>();
    IsolationPolicy policy;
    policy.mode = IsolationMode::All;
    policy.settings.helper = helper();
    policy.settings.timeout_seconds = 2;
    policy.settings.memory_limit = memory_limit;
    r->set_isolation(policy);
    r->load_directories({folder});
    return r;
}

PluginRegistry &faulty()
{
    // 256 MiB: the runaway allocation reaches it in a few 64 MiB steps, well
    // before the timeout, on a loaded machine too.
    static const auto r = isolated(fs::path(ARBOR_FIXTURE_PLUGIN_DIR) / "fixture-faulty", uint64_t{256} << 20);
    return *r;
}

void set(PluginInstance &p, const std::string &id, const std::string &text)
{
    p.set_param(id, parse_param_value(*p.find_param(id), text).value);
}

const Volume &small_phantom()
{
    static const Volume v = [] {
        io::PhantomOptions o;
        o.size = 40;
        o.noise_sigma = 3; // some branches for the simplifier
        return io::make_phantom(io::builtin_phantom("head"), o);
    }();
    return v;
}

Volume filtered(PluginInstance &filter) { return run_filter(filter, small_phantom(), nullptr, uint64_t{1} << 32); }

TEST(PluginIsolation, TheLibraryLoadsInAProcessOfItsOwn)
{
    ASSERT_EQ(faulty().plugins().size(), 6u) << (faulty().refusals().empty() ? "" : faulty().refusals()[0].reason);
    for (const PluginInfo &p : faulty().plugins())
        EXPECT_TRUE(p.library->isolated());
    PluginInstance f = faulty().create("org.arbor.test.faulty-filter");
    ASSERT_EQ(f.param_descriptions().size(), 2u);
    set(f, "fault", "none");
    const Volume out = filtered(f);
    ASSERT_EQ(out.byte_size(), small_phantom().byte_size());
    EXPECT_EQ(std::memcmp(out.data(), small_phantom().data(), out.byte_size()), 0);
    EXPECT_EQ(f.get_param("fault").number[0], 0.0);
}

// Each fault in each call of the filter: a PluginError naming the plugin and
// the call, then, the fault taken away, the same instance works again.
TEST(PluginIsolation, ACrashAbortHangOrRunawayAllocationFailsTheCallAndThePluginComesBack)
{
    struct Case {
        const char *fault, *call, *expect;
    } cases[] = {{"segfault", "first", "crashed (SIGSEGV"},
                 {"segfault", "second", "crashed (SIGSEGV"},
                 {"abort", "second", "crashed (SIGABRT"},
                 {"hang", "first", "did not answer for 2 s"},
                 {"allocate", "second", "crashed (SIGSEGV"}};
    PluginInstance f = faulty().create("org.arbor.test.faulty-filter");
    for (const Case &c : cases) {
        SCOPED_TRACE(std::string(c.fault) + " in the " + c.call + " call");
        set(f, "fault", c.fault);
        set(f, "call", c.call);
        const auto started = std::chrono::steady_clock::now();
        try {
            filtered(f);
            ADD_FAILURE() << "no error";
        } catch (const PluginError &e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("org.arbor.test.faulty-filter"), std::string::npos) << m;
            EXPECT_NE(m.find(c.expect), std::string::npos) << m;
            EXPECT_NE(m.find(std::string(" in filter.") + (c.call[0] == 'f' ? "output_type" : "apply")),
                      std::string::npos)
                << m;
            EXPECT_NE(m.find("restarts it at its next call"), std::string::npos) << m;
        }
        EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(20));
        // The next call starts a new process, sets the parameters again
        // (the fault too), then this one.
        set(f, "fault", "none");
        const Volume out = filtered(f);
        EXPECT_EQ(std::memcmp(out.data(), small_phantom().data(), out.byte_size()), 0);
    }
}

// The pipeline's jobs run on threads that end; a plugin restarted on one
// must outlive it (a child tied to the thread that spawned it would die).
TEST(PluginIsolation, APluginRestartedOnAThreadThatEndsLivesOn)
{
    PluginInstance f = faulty().create("org.arbor.test.faulty-filter");
    set(f, "fault", "segfault");
    set(f, "call", "second");
    EXPECT_THROW(filtered(f), PluginError);
    std::thread([&] { set(f, "fault", "none"); }).join(); // the restart, on a job's thread
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const Volume out = filtered(f);
    EXPECT_EQ(std::memcmp(out.data(), small_phantom().data(), out.byte_size()), 0);
}

TEST(PluginIsolation, ASimplifierThatCrashesOrReturnsNanIsNamed)
{
    const Volume &v = small_phantom();
    const topology::TopologyResult topo = topology::compute_contour_tree(v);
    const topology::FieldView field{v.type(), v.data(), static_cast<uint32_t>(v.voxel_count()), &v.geometry()};
    PluginInstance s = faulty().create("org.arbor.test.faulty-simplifier");
    const topology::BranchDecomposition good = topology::decompose_branches(topo.tree, field, simplifier_importance(s));
    EXPECT_GT(good.branches.size(), 2u);
    for (const char *fault : {"segfault", "nan"}) {
        set(s, "fault", fault);
        set(s, "call", "second");
        try {
            topology::decompose_branches(topo.tree, field, simplifier_importance(s));
            ADD_FAILURE() << fault << ": no error";
        } catch (const std::exception &e) {
            EXPECT_NE(std::string(e.what()).find("org.arbor.test.faulty-simplifier"), std::string::npos) << e.what();
        }
    }
    set(s, "fault", "none");
    const topology::BranchDecomposition again = topology::decompose_branches(topo.tree, field, simplifier_importance(s));
    EXPECT_EQ(again.branches.size(), good.branches.size());
}

// A small simplified tree of the phantom, for depictors and generators.
struct TreeScene {
    topology::TopologyResult topo;
    topology::BranchDecomposition decomposition;
    topology::SimplificationCut cut;
    std::unique_ptr<BranchTreeRecord> tree;
    TreeScene()
    {
        const Volume &v = small_phantom();
        topo = topology::compute_contour_tree(v);
        const topology::FieldView field{v.type(), v.data(), static_cast<uint32_t>(v.voxel_count()), &v.geometry()};
        PluginInstance itri = test::built_plugins().create("org.arbor.simplifier.itri");
        decomposition = topology::decompose_branches(topo.tree, field, simplifier_importance(itri));
        cut = topology::cut_by_count(decomposition, 4);
        tree = std::make_unique<BranchTreeRecord>(topo.tree, decomposition, cut, v);
    }
};

// The calls of one kind, in the order of its interface.
struct KindCalls {
    const char *id;
    std::vector<const char *> calls;
    std::function<void(PluginInstance &)> run;
};

std::vector<KindCalls> every_kind(const TreeScene &scene, const fs::path &file)
{
    const arbor_branch_tree &tree = scene.tree->record();
    return {
        {"org.arbor.test.faulty-importer",
         {"importer.probe", "importer.read_header", "importer.read_voxels"},
         [file](PluginInstance &p) {
             const auto &t = p.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
             int32_t confidence = 0;
             p.check(p.call("importer.probe", t.probe, file.c_str(), nullptr, uint64_t{0}, &confidence),
                     "probing");
             EXPECT_EQ(confidence, 100);
             const Volume v = import_volume(p, file, nullptr, uint64_t{1} << 30);
             EXPECT_EQ(v.value(7 + 8 * (7 + 8 * 7)), 21.0);
         }},
        {"org.arbor.test.faulty-depictor",
         {"depictor.depict", "depictor.related", "depictor.legend"},
         [&tree](PluginInstance &p) {
             arbor_depiction_request request{sizeof(arbor_depiction_request), 0, &tree};
             DepictionRecord record(tree.branch_count);
             depict(p, request, record);
             const auto &t = p.interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
             arbor_bool32 related = 0;
             p.check(p.call("depictor.related", t.related, &tree, 1u, 0u, &related), "relating");
             std::vector<float> pixels(32 * 32 * 4, 0.0f);
             arbor_image image{};
             image.struct_size = sizeof image;
             image.width = image.height = 32;
             image.row_stride = 4 * 32;
             image.rgba = pixels.data();
             Task task;
             p.check(p.call("depictor.legend", t.legend, &request, &image, task.get()), "drawing");
             EXPECT_EQ(pixels[4 * 32 * 32 - 1], 0.5f);
         }},
        {"org.arbor.test.faulty-tf-generator",
         {"tf_generator.generate"},
         [&tree](PluginInstance &p) {
             const arbor_volume view = small_phantom().view();
             DepictionRecord depiction(tree.branch_count);
             arbor_tf_request request{};
             request.struct_size = sizeof request;
             request.tree = &tree;
             request.depiction = &depiction.record();
             request.volume = &view;
             request.value_range[0] = tree.saddle_value[0];
             request.value_range[1] = tree.extremum_value[0];
             request.min_spacing = 1;
             TransferFunctions out(tree.branch_count, 64, 1.0);
             generate_transfer_functions(p, request, out);
             EXPECT_EQ(out.lut(0)[4 * 63 + 3], 1.0f);
         }},
        {"org.arbor.test.faulty-renderer",
         {"renderer.render"},
         [](PluginInstance &p) {
             const Volume &v = small_phantom();
             const arbor_volume view = v.view();
             TransferFunctions tf(1, 16, 1.0);
             test::global_ramp(tf, 0, 255);
             const arbor_camera camera = orbit_camera(v.geometry(), Orbit{});
             const arbor_render_request request = test::global_request(view, tf, camera);
             const RenderedImage image = render_image(p, request, 24, 16);
             EXPECT_EQ(image.rgba[2], 0.6f);
         }},
    };
}

// A segfault in every call of every other kind: named, survived, and the
// plugin works again at its next call.
TEST(PluginIsolation, ASegfaultInAnyCallOfAnyKindIsNamedAndSurvived)
{
    const TreeScene scene;
    const fs::path file = fs::temp_directory_path() / ("arbor-isolation-" + std::to_string(getpid()) + ".faulty");
    std::ofstream(file) << "any content\n";
    for (const KindCalls &kind : every_kind(scene, file)) {
        PluginInstance p = faulty().create(kind.id);
        set(p, "fault", "none");
        kind.run(p);
        for (std::size_t c = 0; c < kind.calls.size(); ++c) {
            SCOPED_TRACE(std::string(kind.id) + " " + kind.calls[c]);
            set(p, "fault", "segfault");
            set(p, "call", c == 0 ? "first" : c == 1 ? "second" : "third");
            try {
                kind.run(p);
                ADD_FAILURE() << "no error";
            } catch (const PluginError &e) {
                const std::string m = e.what();
                EXPECT_NE(m.find(kind.id), std::string::npos) << m;
                EXPECT_NE(m.find(std::string("crashed (SIGSEGV, a segmentation fault) in ") + kind.calls[c]),
                          std::string::npos)
                    << m;
            }
            set(p, "fault", "none");
            kind.run(p);
        }
    }
    fs::remove(file);
}

// Garbage from an isolated plugin meets the host's checks as from any other:
// a role that does not exist, a NaN lookup table, NaN pixels (the
// simplifier's NaN importances are above).
TEST(PluginIsolation, GarbageOutputsAreRefusedNamingThePlugin)
{
    const TreeScene scene;
    for (const KindCalls &kind : every_kind(scene, "unused.faulty")) {
        if (std::string(kind.id).find("importer") != std::string::npos)
            continue; // an importer's garbage is a file format's business (fuzzing)
        PluginInstance p = faulty().create(kind.id);
        set(p, "fault", "nan");
        try {
            kind.run(p);
            ADD_FAILURE() << kind.id << ": NaN accepted";
        } catch (const std::exception &e) {
            EXPECT_NE(std::string(e.what()).find(kind.id), std::string::npos) << e.what();
        }
    }
}

// Arbor's own plugins isolated give what they give in-process: a filter, a
// simplifier's decomposition, a rendering.
TEST(PluginIsolation, OurPluginsGiveTheSameResultsIsolated)
{
    const auto iso = isolated(test::plugin_dir());
    PluginInstance a = test::built_plugins().create("org.arbor.filter.gaussian");
    PluginInstance b = iso->create("org.arbor.filter.gaussian");
    const Volume fa = filtered(a), fb = filtered(b);
    ASSERT_EQ(fa.byte_size(), fb.byte_size());
    EXPECT_EQ(std::memcmp(fa.data(), fb.data(), fa.byte_size()), 0);

    const Volume &v = small_phantom();
    const topology::TopologyResult topo = topology::compute_contour_tree(v);
    const topology::FieldView field{v.type(), v.data(), static_cast<uint32_t>(v.voxel_count()), &v.geometry()};
    PluginInstance ia = test::built_plugins().create("org.arbor.simplifier.itri");
    PluginInstance ib = iso->create("org.arbor.simplifier.itri");
    const auto da = topology::decompose_branches(topo.tree, field, simplifier_importance(ia));
    const auto db = topology::decompose_branches(topo.tree, field, simplifier_importance(ib));
    ASSERT_EQ(da.branches.size(), db.branches.size());
    for (std::size_t i = 0; i < da.branches.size(); ++i)
        ASSERT_EQ(da.branches[i].importance, db.branches[i].importance) << i;
}

} // namespace
} // namespace arbor
