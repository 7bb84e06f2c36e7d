#include "view_flags.hpp"

#include "host/host_services.hpp"

namespace arbor::cli {

using pipeline::short_name;

void ViewFlags::add_to(CLI::App &command, Context &context)
{
    renderer_option_ = command.add_option("--renderer", renderer_,
                                          "Renderer plugin: auto (the default: the OpenGL ray caster on graphics "
                                          "hardware, else the CPU ray caster) or a short name or id of those loaded (" +
                                              plugin_names(context.registry, ARBOR_KIND_RENDERER) + ")")
                           ->group("Rendering");
    width_option_ = command.add_option("--width", width_, "Image width in pixels (default 512)")
                        ->check(CLI::Range(16, 8192))->group("Rendering");
    height_option_ = command.add_option("--height", height_, "Image height in pixels (default 512)")
                         ->check(CLI::Range(16, 8192))->group("Rendering");
    azimuth_option_ =
        command.add_option("--azimuth", azimuth_, "Camera azimuth in degrees (0: from anterior, 90: from the left)")
            ->group("Rendering");
    elevation_option_ = command.add_option("--elevation", elevation_, "Camera elevation in degrees (90: from superior)")
                            ->check(CLI::Range(-90.0, 90.0))->group("Rendering");
    zoom_option_ = command.add_option("--zoom", zoom_, "Zoom (1 fits the volume)")
                       ->check(CLI::Range(0.05, 50.0))->group("Rendering");
    auto *ortho = command.add_flag("--orthographic", orthographic_, "Orthographic instead of perspective projection")
                      ->group("Rendering");
    auto *persp = command.add_flag("--perspective", perspective_, "Perspective projection (the default)")
                      ->group("Rendering");
    ortho->excludes(persp);
    background_option_ =
        command.add_option("--background", background_, "Background colour r,g,b[,a] in [0, 1] (default black)")
            ->delimiter(',')
            ->expected(3, 4)
            ->check(CLI::Range(0.0, 1.0))
            ->group("Rendering");
    view_option_ = command.add_option("--view", view_,
                                      "auto: choose azimuth and elevation from the structures (the direction that "
                                      "shows the important inner ones best); fixed: --azimuth/--elevation (default)")
                       ->check(CLI::IsMember({"auto", "fixed"}))
                       ->group("Rendering");
    framing_option_ = command.add_option("--framing", framing_,
                                         "content: frame what is visible, 85 % of the shorter side (default); "
                                         "volume: fit the whole grid")
                          ->check(CLI::IsMember({"content", "volume"}))
                          ->group("Rendering");
    flags_.add(command, context.registry, ARBOR_KIND_RENDERER, "Renderer options");
    context.flag_names.add(flags_);
}

void ViewFlags::apply(pipeline::ViewChoice &view, const pipeline::PluginCatalog &catalog) const
{
    const std::string name = renderer_option_->count() ? renderer_ : view.renderer.id;
    if (renderer_option_->count())
        view.renderer = {catalog.find(ARBOR_KIND_RENDERER, renderer_), "", {}};
    else if (!view.renderer.id.empty())
        view.renderer.id = catalog.find(ARBOR_KIND_RENDERER, view.renderer.id);
    if (name == "auto") { // flags for one renderer choose it; else the machine does; say which and why
        const std::vector<std::string> flagged = flags_.given_plugins();
        if (flagged.size() == 1) {
            view.renderer.id = flagged.front();
            log_message(ARBOR_LOG_INFO, "", "renderer " + short_name(view.renderer.id) + ": its options were given");
        } else {
            log_message(ARBOR_LOG_INFO, "", "renderer " + short_name(view.renderer.id) + ": " +
                                                catalog.renderer_choice().reason);
        }
    }
    flags_.apply(view.renderer);
    if (width_option_->count())
        view.width = width_;
    if (height_option_->count())
        view.height = height_;
    if (azimuth_option_->count())
        view.orbit.azimuth = azimuth_;
    if (elevation_option_->count())
        view.orbit.elevation = elevation_;
    if (zoom_option_->count())
        view.orbit.zoom = zoom_;
    if (orthographic_)
        view.orbit.perspective = false;
    if (perspective_)
        view.orbit.perspective = true;
    if (view_option_->count())
        view.auto_view = view_ == "auto";
    if (framing_option_->count())
        view.frame_content = framing_ == "content";
    if (background_option_->count())
        for (std::size_t c = 0; c < 4; ++c)
            view.background[c] = c < background_.size() ? background_[c] : 1.0;
}

} // namespace arbor::cli
