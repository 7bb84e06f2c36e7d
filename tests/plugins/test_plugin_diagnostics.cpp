// What a plugin author and a user are told when a plugin misbehaves (issue
// 20): a crash inside a plugin call names the plugin and the call before the
// process dies of the signal; `arbor plugin-check` finds the bugs of plugins
// it used to pass (an importance that is NaN for a batch of one row, a
// generator deaf to cancellation, a filter that refuses tiny volumes without
// a word) and shows the plugin's last error with every failure.
#include "test_paths.hpp"

#include "host/conformance.hpp"
#include "host/filter_run.hpp"
#include "host/plugin_call.hpp"
#include "host/plugin_registry.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <map>
#include <string>

namespace arbor {
namespace {

namespace fs = std::filesystem;

fs::path fixture(const std::string &folder, const std::string &name)
{
    return fs::path(ARBOR_FIXTURE_PLUGIN_DIR) / folder / (name + ".so");
}

// Loads one fixture library and filters a small volume with its plugin.
void filter_with(const fs::path &library, const std::string &id)
{
    PluginRegistry registry;
    registry.load_file(library);
    PluginInstance filter = registry.create(id);
    Geometry g;
    g.dims = {4, 4, 4};
    const Volume input = Volume::allocate(ARBOR_VOXEL_U8, g, {}, uint64_t{1} << 20);
    run_filter(filter, input, nullptr, uint64_t{1} << 20, {});
}

class CrashReport : public testing::Test {
protected:
    void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

TEST_F(CrashReport, ASegfaultInAPluginCallNamesThePluginAndTheCall)
{
    EXPECT_EXIT(filter_with(fixture("", "fixture-crash"), "org.arbor.test.crash"), testing::KilledBySignal(SIGSEGV),
                "arbor: plugin org\\.arbor\\.test\\.crash crashed \\(SIGSEGV\\) in filter\\.apply\n");
}

TEST_F(CrashReport, AnAbortInAPluginCallNamesThePluginAndTheCall)
{
    EXPECT_EXIT(filter_with(fixture("fixture-abort", "fixture-abort"), "org.arbor.test.abort"),
                testing::KilledBySignal(SIGABRT),
                "arbor: plugin org\\.arbor\\.test\\.abort crashed \\(SIGABRT\\) in filter\\.apply\n");
}

TEST_F(CrashReport, ACrashOnAPluginsOwnThreadNamesTheCallInProgress)
{
    EXPECT_EXIT(filter_with(fixture("fixture-crash-thread", "fixture-crash-thread"), "org.arbor.test.crash-thread"),
                testing::KilledBySignal(SIGSEGV),
                "arbor: crashed \\(SIGSEGV\\) on a thread outside the host's plugin calls while plugin "
                "org\\.arbor\\.test\\.crash-thread was in filter\\.apply\n");
}

TEST_F(CrashReport, ACrashOutsidePluginCallsIsLeftAlone)
{
    const auto crash_after_a_call = [] {
        { const PluginCall call("org.example.done", "filter.apply"); } // installs the handlers, then ends
        std::raise(SIGSEGV);
    };
    EXPECT_EXIT(crash_after_a_call(), testing::KilledBySignal(SIGSEGV), "^$"); // nothing said
}

TEST_F(CrashReport, NestedCallsRestoreTheOuterOne)
{
    const auto crash_in_outer = [] {
        const PluginCall outer("org.example.outer", "renderer.render");
        { const PluginCall inner("org.example.inner", "params.get"); }
        std::raise(SIGFPE);
    };
    EXPECT_EXIT(crash_in_outer(), testing::KilledBySignal(SIGFPE),
                "^arbor: plugin org\\.example\\.outer crashed \\(SIGFPE\\) in renderer\\.render\n$");
}

// The failed checks of a report, by name.
std::map<std::string, std::string> failures(const ConformanceReport &r)
{
    std::map<std::string, std::string> out;
    for (const ConformanceCheck &c : r.checks)
        if (!c.passed)
            out[c.name] = c.detail;
    return out;
}

TEST(PluginCheckFinds, AnImportanceThatIsNotFiniteForABatchOfOneRow)
{
    const auto failed =
        failures(check_plugin_conformance(fixture("fixture-simplifier-batch", "fixture-simplifier-batch"),
                                          std::chrono::seconds(60)));
    EXPECT_EQ(failed.count("simplifier on host measures"), 0u); // what it passed before
    ASSERT_EQ(failed.count("simplifier on one row"), 1u);
    EXPECT_EQ(failed.at("simplifier on one row"),
              "importance of the root's row alone: row 0 got NaN, not a finite number >= 0 (last_error: empty)");
    ASSERT_EQ(failed.count("simplifier rows are independent"), 1u);
    EXPECT_NE(failed.at("simplifier rows are independent").find("must depend on its own row only"), std::string::npos)
        << failed.at("simplifier rows are independent");
}

TEST(PluginCheckFinds, AGeneratorThatIgnoresCancellation)
{
    const auto failed = failures(check_plugin_conformance(
        fixture("fixture-generator-deaf", "fixture-generator-deaf"), std::chrono::seconds(60)));
    EXPECT_EQ(failed.count("tf-generator on a small tree"), 0u);
    ASSERT_EQ(failed.count("tf-generator cancelled mid-call"), 1u) << ::testing::PrintToString(failed);
    const std::string &detail = failed.at("tf-generator cancelled mid-call");
    EXPECT_EQ(detail.rfind("generate(20000 branches) went on for ", 0), 0u) << detail;
    EXPECT_NE(detail.find(" ms after its task was cancelled; poll task->cancelled at least every 0.1 s"),
              std::string::npos)
        << detail;
    // It went on for about the rest of its 3 s: far more than the 1 s of grace.
    EXPECT_GT(std::stol(detail.substr(std::string("generate(20000 branches) went on for ").size())), 1500) << detail;
    EXPECT_EQ(failed.size(), 1u) << ::testing::PrintToString(failed);
}

TEST(PluginCheckFinds, AFilterThatRefusesTinyVolumesWithoutAMessage)
{
    const auto failed = failures(
        check_plugin_conformance(fixture("fixture-tiny-mute", "fixture-tiny-mute"), std::chrono::seconds(60)));
    EXPECT_EQ(failed.count("filter on every voxel type"), 0u);
    ASSERT_EQ(failed.count("filter on tiny and thin volumes"), 1u) << ::testing::PrintToString(failed);
    EXPECT_EQ(failed.at("filter on tiny and thin volumes"),
              "apply on 1x1x1 u8 returned invalid argument (-1) without a last_error message (last_error: empty)");
    EXPECT_EQ(failed.size(), 1u) << ::testing::PrintToString(failed);
}

TEST(PluginCheckFinds, ACrashAndNamesTheCheckItHappenedIn)
{
    const auto failed =
        failures(check_plugin_conformance(fixture("", "fixture-crash"), std::chrono::seconds(60)));
    ASSERT_EQ(failed.count("filter invalid arguments"), 1u) << ::testing::PrintToString(failed);
    EXPECT_EQ(failed.at("filter invalid arguments"),
              "crashed with signal 11 (Segmentation fault) during 'filter invalid arguments'");
}

TEST(PluginCheckFinds, NothingWrongWithAThirdPartysGoodSimplifier)
{
    const ConformanceReport r =
        check_plugin_conformance(fixture("fixture-simplifier", "fixture-simplifier"), std::chrono::seconds(60));
    EXPECT_TRUE(r.passed()) << ::testing::PrintToString(failures(r));
}

} // namespace
} // namespace arbor
