// library.cpp - the entry point of arbor-renderer-cpu: the CPU ray caster.
#include <arbor/sdk/instance.hpp>

namespace arbor::raycast {
extern const arbor_plugin_descriptor kRayCasterDescriptor;
sdk::Instance *create_ray_caster(const arbor_host *host);
} // namespace arbor::raycast

namespace {

const arbor::sdk::PluginClass kRenderers[] = {
    {&arbor::raycast::kRayCasterDescriptor, &arbor::raycast::create_ray_caster},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kRenderers)
