// The plugins built in this tree load, and every one of them offers the
// interface of its kind.
#include "plugin_fixture.hpp"

#include "host/descriptor_rules.hpp"

#include <gtest/gtest.h>

namespace arbor {
namespace {

TEST(PluginRegistry, BuiltPluginsLoadWithoutRefusals)
{
    const PluginRegistry &registry = test::built_plugins();
    for (const PluginRefusal &r : registry.refusals())
        ADD_FAILURE() << r.path << " " << r.plugin_id << ": " << r.reason;
    EXPECT_FALSE(registry.plugins().empty());
    for (const PluginInfo &p : registry.plugins()) {
        PluginInstance instance = registry.create(p.descriptor->id);
        EXPECT_NE(instance.get()->get_interface(instance.get(), kind_interface_id(p.descriptor->kind)),
                  nullptr)
            << p.descriptor->id;
    }
}

} // namespace
} // namespace arbor
