// renderer_choice.cpp - PluginCatalog::renderer_choice: which ray caster
// "auto" means on this machine.  The OpenGL ray caster is asked what its
// context runs on (arbor.render-device/1): graphics hardware wins; OpenGL
// emulated on the CPU (llvmpipe, softpipe) is slower than the CPU ray
// caster (PLATFORM_NOTES: 3.6-3.9 fps against 20+), so then the CPU.
#include "plugin_catalog.hpp"

#include "host/plugin_registry.hpp"
#include "host/rendering.hpp"

namespace arbor::pipeline {

namespace {

constexpr const char *kGl = "org.arbor.renderer.gl-raycast", *kCpu = "org.arbor.renderer.cpu-raycast";

bool has(const PluginRegistry &registry, const char *id)
{
    for (const PluginInfo *p : registry.plugins_of_kind(ARBOR_KIND_RENDERER))
        if (std::string(p->descriptor->id) == id)
            return true;
    return false;
}

} // namespace

const PluginCatalog::RendererChoice &PluginCatalog::renderer_choice() const
{
    std::call_once(choice_once_, [&] {
        if (!has(registry_, kCpu)) {
            choice_ = {has(registry_, kGl) ? kGl : kCpu,
                       "the CPU ray caster is not installed"};
            return;
        }
        if (!has(registry_, kGl)) {
            choice_ = {kCpu, "the OpenGL ray caster is not installed"};
            return;
        }
        try {
            const PluginInstance gl = create(kGl);
            const RenderDevice device = render_device(gl);
            if (device.kind == ARBOR_DEVICE_GPU)
                choice_ = {kGl, "the OpenGL ray caster runs on graphics hardware (" + device.name + ")"};
            else
                choice_ = {kCpu, "the OpenGL ray caster would run on " + device.name +
                                     ", graphics emulated on the CPU, slower than the CPU ray caster"};
        } catch (const std::exception &e) {
            choice_ = {kCpu, std::string("the OpenGL ray caster cannot start: ") + e.what()};
        }
    });
    return choice_;
}

} // namespace arbor::pipeline
