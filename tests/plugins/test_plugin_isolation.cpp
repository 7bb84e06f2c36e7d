// Plugin isolation (host/isolated_library.hpp): plugins in arbor-plugin-host
// give the same results as in-process, and a crash, abort, hang or runaway
// allocation fails the call with a message naming the plugin and the call,
// while this process carries on and the plugin comes back at its next call.
#include "plugin_fixture.hpp"
#include "topology_oracles.hpp"

#include "host/filter_run.hpp"
#include "host/param_text.hpp"
#include "host/simplifier_importance.hpp"
#include "io/phantom.hpp"
#include "topology/branch_decomposition.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>

namespace arbor {
namespace {

namespace fs = std::filesystem;

fs::path helper()
{
    return fs::read_symlink("/proc/self/exe").parent_path() / "arbor-plugin-host";
}

// Every library of `folder` isolated: a timeout of 2 s, a memory limit of 1 GiB.
std::unique_ptr<PluginRegistry> isolated(const fs::path &folder)
{
    auto r = std::make_unique<PluginRegistry>();
    IsolationPolicy policy;
    policy.mode = IsolationMode::All;
    policy.settings.helper = helper();
    policy.settings.timeout_seconds = 2;
    policy.settings.memory_limit = uint64_t{1} << 30;
    r->set_isolation(policy);
    r->load_directories({folder});
    return r;
}

PluginRegistry &faulty()
{
    static const auto r = isolated(fs::path(ARBOR_FIXTURE_PLUGIN_DIR) / "fixture-faulty");
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
    ASSERT_EQ(faulty().plugins().size(), 2u) << (faulty().refusals().empty() ? "" : faulty().refusals()[0].reason);
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
