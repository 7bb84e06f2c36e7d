// library.cpp - the entry point of arbor-renderer-gl: the OpenGL ray caster.
#include <arbor/sdk/instance.hpp>

namespace arbor::glraycast {
extern const arbor_plugin_descriptor kGlRayCasterDescriptor;
sdk::Instance *create_gl_ray_caster(const arbor_host *host);
} // namespace arbor::glraycast

namespace {

const arbor::sdk::PluginClass kRenderers[] = {
    {&arbor::glraycast::kGlRayCasterDescriptor, &arbor::glraycast::create_gl_ray_caster},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kRenderers)
