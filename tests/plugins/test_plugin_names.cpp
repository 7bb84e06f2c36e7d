// A plugin's short name comes from its own id, whatever else is installed;
// a short name two plugins of a kind share names neither and says so, and
// full ids always work (issue 20: a second plugin whose id also ended in
// ".pv" silently took over "--simplifier pv").
#include "test_paths.hpp"

#include "host/plugin_registry.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <gtest/gtest.h>

namespace arbor {
namespace {

namespace fs = std::filesystem;

fs::path fixture_folder(const std::string &name)
{
    return fs::path(ARBOR_FIXTURE_PLUGIN_DIR) / name;
}

std::string names_error(const pipeline::PluginCatalog &catalog, std::string_view kind, const std::string &name)
{
    try {
        const std::string id = catalog.find(kind, name);
        return "found " + id;
    } catch (const pipeline::PluginNameError &e) {
        return e.what();
    }
}

TEST(PluginNames, ShortNameIsTheLastPartOfTheIdAlone)
{
    EXPECT_EQ(plugin_short_name("org.arbor.simplifier.itri"), "itri");
    EXPECT_EQ(plugin_short_name("org.example.simplifier.n-measure"), "n-measure");
    EXPECT_EQ(plugin_short_name("nodots"), "nodots");
    EXPECT_EQ(pipeline::short_name("org.other.simplifier.pv"), "pv");
}

TEST(PluginNames, AThirdPartysShortNameWorksWhileItIsTheOnlyOne)
{
    PluginRegistry registry;
    registry.load_directories({test::plugin_dir(), fixture_folder("fixture-pv-a")});
    const pipeline::PluginCatalog catalog(registry);
    EXPECT_EQ(catalog.find(ARBOR_KIND_SIMPLIFIER, "pv"), "org.example.simplifier.pv");
    EXPECT_EQ(catalog.find(ARBOR_KIND_SIMPLIFIER, "itri"), "org.arbor.simplifier.itri");
    EXPECT_EQ(registry.sharing_short_name("pv").size(), 1u);
}

TEST(PluginNames, ASharedShortNameNamesBothPluginsAndHowToWriteThem)
{
    PluginRegistry registry;
    registry.load_directories({test::plugin_dir(), fixture_folder("fixture-pv-a"), fixture_folder("fixture-pv-b")});
    const pipeline::PluginCatalog catalog(registry);
    ASSERT_EQ(registry.sharing_short_name("pv").size(), 2u);
    const std::string message = names_error(catalog, ARBOR_KIND_SIMPLIFIER, "pv");
    EXPECT_EQ(message, "simplifier 'pv' is ambiguous: org.example.simplifier.pv and org.other.simplifier.pv both "
                       "have the short name 'pv'; write the full id (org.example.simplifier.pv or "
                       "org.other.simplifier.pv)");
    // Full ids always work; plugins that share nothing are untouched.
    EXPECT_EQ(catalog.find(ARBOR_KIND_SIMPLIFIER, "org.example.simplifier.pv"), "org.example.simplifier.pv");
    EXPECT_EQ(catalog.find(ARBOR_KIND_SIMPLIFIER, "org.other.simplifier.pv"), "org.other.simplifier.pv");
    EXPECT_EQ(catalog.find(ARBOR_KIND_SIMPLIFIER, "itri"), "org.arbor.simplifier.itri");
    EXPECT_EQ(catalog.find(ARBOR_KIND_FILTER, "gaussian"), "org.arbor.filter.gaussian");
}

TEST(PluginNames, TheLoadOrderDoesNotChooseBetweenPluginsSharingAName)
{
    // Which folder comes first decides nothing: the name stays ambiguous.
    PluginRegistry registry;
    registry.load_directories({fixture_folder("fixture-pv-b"), fixture_folder("fixture-pv-a")});
    const pipeline::PluginCatalog catalog(registry);
    EXPECT_NE(names_error(catalog, ARBOR_KIND_SIMPLIFIER, "pv").find("is ambiguous"), std::string::npos);
}

TEST(PluginNames, AShortNameOfAnotherKindDoesNotGetInTheWay)
{
    // "pv" is a simplifier here; as a filter name it is simply unknown.
    PluginRegistry registry;
    registry.load_directories({test::plugin_dir(), fixture_folder("fixture-pv-a")});
    const pipeline::PluginCatalog catalog(registry);
    const std::string message = names_error(catalog, ARBOR_KIND_FILTER, "pv");
    EXPECT_EQ(message.rfind("no filter 'pv' (there are: ", 0), 0u) << message;
    EXPECT_NE(message.find("org.arbor.filter.gaussian"), std::string::npos) << message;
}

TEST(PluginNames, DefaultsAreFullIdsSoNoThirdPartyChangesThem)
{
    const pipeline::Document d = pipeline::default_document();
    for (const std::string &id : {d.simplifier.id, d.appearance.depictor.id, d.appearance.generator.id,
                                  d.appearance.legend.id})
        EXPECT_EQ(id.rfind("org.arbor.", 0), 0u) << id;
}

} // namespace
} // namespace arbor
