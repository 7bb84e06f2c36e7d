// render_options.hpp - what the rendering commands (run, render) share: the
// renderer plugin and its flags, the orbit camera, image size and
// background, and the step from transfer functions and labels to an image.
#pragma once

#include "plugin_choice.hpp"

#include "host/rendering.hpp"
#include "host/tf_generation.hpp"

#include <array>
#include <string>

namespace arbor::cli {

class RenderOptions {
public:
    void add_to(CLI::App &command, Context &context);

    // Renders `volume` classified by `labels` (may be empty: all label 0).
    RenderedImage render(const Volume &volume, const std::vector<uint32_t> &labels, const TransferFunctions &tf,
                         Context &context);
    PluginInstance &renderer() { return *renderer_; }
    const Orbit &orbit() const { return orbit_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

private:
    PluginChoice renderers_{ARBOR_KIND_RENDERER, "renderer"};
    std::string renderer_name_ = "cpu-raycast";
    PluginInstance *renderer_ = nullptr;
    Orbit orbit_;
    bool orthographic_ = false;
    uint32_t width_ = 512, height_ = 512;
    std::vector<float> background_{0.0f, 0.0f, 0.0f, 1.0f};
};

} // namespace arbor::cli
