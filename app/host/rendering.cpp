#include "rendering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace arbor {

RenderedImage render_image(PluginInstance &renderer, const arbor_render_request &request, uint32_t width,
                           uint32_t height, ProgressSink *progress, std::stop_token stop)
{
    const auto &table = renderer.interface<arbor_renderer_v1>(ARBOR_INTERFACE_RENDERER);
    RenderedImage image;
    image.width = width;
    image.height = height;
    image.rgba.assign(std::size_t{width} * height * 4, 0.0f);
    image.depth.assign(std::size_t{width} * height, std::numeric_limits<float>::infinity());
    arbor_image out{};
    out.struct_size = sizeof out;
    out.width = width;
    out.height = height;
    out.row_stride = 4 * static_cast<int64_t>(width);
    out.rgba = image.rgba.data();
    out.depth = image.depth.data();
    // NaN: "not measured"; a renderer that measures visibility overwrites all.
    image.label_visibility.assign(request.transfer_functions->branch_count, std::numeric_limits<double>::quiet_NaN());
    out.label_visibility = image.label_visibility.data();
    out.label_visibility_count = static_cast<uint32_t>(image.label_visibility.size());
    Task task(progress, std::move(stop));
    renderer.check(table.render(renderer.get(), &request, &out, task.get()), "rendering");
    for (float x : image.rgba)
        if (!(x >= 0.0f && x <= 1.0f))
            throw PluginError(ARBOR_ERROR_OUT_OF_RANGE, renderer.id() + " wrote a pixel value outside [0, 1]");
    const auto measured = [](double v) { return !std::isnan(v); };
    if (std::none_of(image.label_visibility.begin(), image.label_visibility.end(), measured)) {
        image.label_visibility.clear();
    } else {
        // A ray's contributions sum to its opacity, at most 1: the total is
        // at most the number of pixels.
        double total = 0;
        for (double v : image.label_visibility) {
            if (!(v >= 0.0) || !std::isfinite(v))
                throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                                  renderer.id() + " measured a visibility that is not a finite number >= 0 (or "
                                                  "left some labels unmeasured)");
            total += v;
        }
        if (total > 1.0001 * static_cast<double>(width) * height)
            throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                              renderer.id() + " measured more visibility than the image's pixels can hold");
    }
    return image;
}

arbor_camera orbit_camera(const Geometry &g, const Orbit &orbit)
{
    // Centre and bounding radius of the volume in LPS.
    std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (int corner = 0; corner < 8; ++corner) {
        const int64_t i = (corner & 1) ? g.dims[0] - 1 : 0, j = (corner & 2) ? g.dims[1] - 1 : 0,
                      k = (corner & 4) ? g.dims[2] - 1 : 0;
        const auto p = g.position_of(i + g.dims[0] * (j + g.dims[1] * k));
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
    }
    const std::array<double, 3> centre{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    const double radius = 0.5 * std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) + 1e-9;
    const double az = orbit.azimuth * M_PI / 180.0, el = orbit.elevation * M_PI / 180.0;
    // Anterior is -y in LPS; azimuth turns towards +x (left).
    const std::array<double, 3> towards_camera{std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el)};
    const double zoom = orbit.zoom > 0 ? orbit.zoom : 1.0;
    arbor_camera c{};
    c.struct_size = sizeof c;
    c.projection = orbit.perspective ? ARBOR_PROJECTION_PERSPECTIVE : ARBOR_PROJECTION_ORTHOGRAPHIC;
    c.view_angle = orbit.view_angle;
    c.parallel_scale = radius / zoom;
    const double distance = orbit.perspective ? radius / std::sin(orbit.view_angle * M_PI / 360.0) / zoom : 3 * radius;
    for (int a = 0; a < 3; ++a) {
        c.focal_point[a] = centre[a];
        c.position[a] = centre[a] + distance * towards_camera[a];
    }
    // Superior is up, tilted with the elevation.
    c.view_up[0] = -std::sin(az) * std::sin(el);
    c.view_up[1] = std::cos(az) * std::sin(el);
    c.view_up[2] = std::cos(el);
    return c;
}

} // namespace arbor
