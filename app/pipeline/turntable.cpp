#include "turntable.hpp"

#include "render_scene.hpp"

#include "core/cancelled.hpp"
#include "core/stopwatch.hpp"
#include "host/rendering.hpp"

#include <stdexcept>

namespace arbor::pipeline {

const char *quality_name(TurntableQuality q)
{
    switch (q) {
    case TurntableQuality::coarse: return "coarse";
    case TurntableQuality::full: return "full";
    case TurntableQuality::supersampled: return "supersampled";
    }
    return "full";
}

TurntableQuality parse_quality(const std::string &text)
{
    for (const TurntableQuality q : {TurntableQuality::coarse, TurntableQuality::full, TurntableQuality::supersampled})
        if (text == quality_name(q))
            return q;
    throw std::invalid_argument("'" + text + "' is not a quality (coarse, full or supersampled)");
}

void render_turntable(Pipeline &pipeline, const TurntableOptions &options,
                      const std::function<void(const TurntableFrame &)> &sink, std::stop_token stop)
{
    if (options.frames == 0)
        throw std::invalid_argument("a turntable needs at least one frame");
    const auto render = pipeline.run<Stage::Render>();
    const auto labels = pipeline.run<Stage::Labels>();
    const auto filtered = pipeline.run<Stage::Filter>();
    const Document document = pipeline.document();
    const ViewChoice &v = document.view;
    const Volume &volume = *filtered->volume;

    PluginInstance renderer = pipeline.catalog().create(v.renderer.id);
    apply_setting(renderer, v.renderer);
    if (options.quality != TurntableQuality::full && !renders_passes(renderer))
        throw std::invalid_argument(renderer.id() + " offers arbor.renderer/1 only: no " +
                                    quality_name(options.quality) + " passes");
    RenderScene scene(*filtered, *labels, render->functions->branch_count(), v.background);
    arbor_render_request &request = scene.request;
    request.transfer_functions = &render->functions->record();
    // The render's framing, as a zoom about the volume's centre.
    Orbit orbit = v.orbit;
    const double azimuth0 = render->viewpoint ? render->viewpoint->azimuth : v.orbit.azimuth;
    if (render->viewpoint)
        orbit.elevation = render->viewpoint->elevation;
    orbit.zoom = (render->framing ? render->framing->scale : 1.0) * (v.orbit.zoom > 0 ? v.orbit.zoom : 1.0);
    const FramePass coarse{ARBOR_RENDER_PASS_COARSE, 0, 1}, full{ARBOR_RENDER_PASS_FULL, 0, 1};
    for (uint32_t f = 0; f < options.frames; ++f) {
        throw_if_stopped(stop);
        TurntableFrame frame;
        frame.index = f;
        frame.azimuth = azimuth0 + 360.0 * f / options.frames;
        orbit.azimuth = frame.azimuth;
        const arbor_camera camera = orbit_camera(volume.geometry(), orbit);
        request.camera = &camera;
        Stopwatch whole, pass;
        frame.image = render_image(renderer, request, v.width, v.height, nullptr, stop,
                                   options.quality == TurntableQuality::coarse ? coarse : full);
        frame.pass_seconds.push_back(pass.lap());
        if (options.quality == TurntableQuality::supersampled)
            for (uint32_t s = 1; s <= options.supersamples; ++s) {
                render_region(renderer, request, frame.image, {}, {ARBOR_RENDER_PASS_SUPERSAMPLE, s, 1}, nullptr, stop);
                frame.pass_seconds.push_back(pass.lap());
            }
        frame.seconds = whole.lap();
        sink(frame);
    }
}

} // namespace arbor::pipeline
