#include "render_options.hpp"

namespace arbor::cli {

void RenderOptions::add_to(CLI::App &command, Context &context)
{
    command.add_option("--renderer", renderer_name_, "Renderer plugin (id or last part)")
        ->default_val("cpu-raycast")
        ->group("Rendering");
    command.add_option("--width", width_, "Image width in pixels")->check(CLI::Range(16, 8192))->group("Rendering");
    command.add_option("--height", height_, "Image height in pixels")->check(CLI::Range(16, 8192))->group("Rendering");
    command.add_option("--azimuth", orbit_.azimuth, "Camera azimuth in degrees (0: from anterior, 90: from the left)")
        ->group("Rendering");
    command.add_option("--elevation", orbit_.elevation, "Camera elevation in degrees (90: from superior)")
        ->check(CLI::Range(-90.0, 90.0))
        ->group("Rendering");
    command.add_option("--zoom", orbit_.zoom, "Zoom (1 fits the volume)")->check(CLI::Range(0.05, 50.0))->group("Rendering");
    command.add_flag("--orthographic", orthographic_, "Orthographic instead of perspective projection")
        ->group("Rendering");
    command.add_option("--background", background_, "Background colour r,g,b[,a] in [0, 1] (default black)")
        ->delimiter(',')
        ->expected(3, 4)
        ->check(CLI::Range(0.0, 1.0))
        ->group("Rendering");
    renderers_.add_to(command, context, "Renderer options");
}

RenderedImage RenderOptions::render(const Volume &volume, const std::vector<uint32_t> &labels,
                                    const TransferFunctions &tf, Context &context)
{
    renderer_ = &renderers_.resolve(renderer_name_);
    orbit_.perspective = !orthographic_;
    const arbor_volume view = volume.view();
    arbor_label_map map{};
    map.struct_size = sizeof map;
    map.label_count = tf.branch_count();
    for (int a = 0; a < 3; ++a)
        map.dims[a] = volume.geometry().dims[a];
    map.labels = labels.data();
    const arbor_camera camera = orbit_camera(volume.geometry(), orbit_);
    arbor_render_request request{};
    request.struct_size = sizeof request;
    request.volume = &view;
    request.labels = labels.empty() ? nullptr : &map;
    request.transfer_functions = &tf.record();
    request.camera = &camera;
    for (std::size_t c = 0; c < 4; ++c)
        request.background[c] = c < background_.size() ? background_[c] : 1.0f;
    request.volume_revision = 1;
    request.labels_revision = 1;
    return render_image(*renderer_, request, width_, height_, &context.progress, context.stop.get_token());
}

} // namespace arbor::cli
