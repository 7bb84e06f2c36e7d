// view_flags.hpp - the flags of what an image looks from and at: the orbit
// camera, image size, background and the renderer with its parameters.
// Only the flags given change the document.
#pragma once

#include "cli_context.hpp"
#include "plugin_flags.hpp"

#include "pipeline/document.hpp"
#include "pipeline/plugin_catalog.hpp"

#include <string>
#include <vector>

namespace arbor::cli {

class ViewFlags {
public:
    void add_to(CLI::App &command, Context &context);
    void apply(pipeline::ViewChoice &view, const pipeline::PluginCatalog &catalog) const;

private:
    std::string renderer_;
    uint32_t width_ = 512, height_ = 512;
    double azimuth_ = 0, elevation_ = 0, zoom_ = 1;
    bool orthographic_ = false, perspective_ = false;
    std::string view_, framing_;
    std::vector<double> background_;
    CLI::Option *renderer_option_ = nullptr, *width_option_ = nullptr, *height_option_ = nullptr,
                *azimuth_option_ = nullptr, *elevation_option_ = nullptr, *zoom_option_ = nullptr,
                *background_option_ = nullptr, *view_option_ = nullptr, *framing_option_ = nullptr;
    PluginFlags flags_;
};

} // namespace arbor::cli
