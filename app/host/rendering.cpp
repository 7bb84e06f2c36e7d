#include "rendering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace arbor {

namespace {

void check_region(const PluginInstance &renderer, RenderedImage &frame, const Region &r, std::size_t labels)
{
    for (uint32_t y = r.y; y < r.y + r.height; ++y) {
        const float *row = frame.rgba.data() + (std::size_t{y} * frame.width + r.x) * 4;
        for (std::size_t i = 0; i < std::size_t{r.width} * 4; ++i)
            if (!(row[i] >= 0.0f && row[i] <= 1.0f))
                throw PluginError(ARBOR_ERROR_OUT_OF_RANGE, renderer.id() + " wrote a pixel value outside [0, 1]");
    }
    std::vector<double> &v = frame.label_visibility;
    const auto measured = [](double x) { return !std::isnan(x); };
    if (std::none_of(v.begin(), v.end(), measured)) {
        v.clear();
        return;
    }
    // A ray's contributions sum to its opacity, at most 1: the total is at
    // most the number of pixels.
    double total = 0;
    for (double x : v) {
        if (!(x >= 0.0) || !std::isfinite(x))
            throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                              renderer.id() + " measured a visibility that is not a finite number >= 0 (or "
                                              "left some labels unmeasured)");
        total += x;
    }
    if (v.size() != labels || total > 1.0001 * static_cast<double>(r.width) * r.height)
        throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                          renderer.id() + " measured more visibility than the image's pixels can hold");
}

// The arbor.renderer/2 request for `pass` of `region` of a frame.
arbor_render_request_v2 pass_request(const arbor_render_request &request, const FramePass &pass, uint32_t width,
                                     uint32_t height, const Region &region)
{
    arbor_render_request_v2 r{};
    r.struct_size = sizeof r;
    r.pass = pass.pass;
    r.volume = request.volume;
    r.labels = request.labels;
    r.transfer_functions = request.transfer_functions;
    r.camera = request.camera;
    std::copy(std::begin(request.background), std::end(request.background), r.background);
    r.volume_revision = request.volume_revision;
    r.labels_revision = request.labels_revision;
    r.transfer_functions_revision = pass.transfer_functions_revision;
    r.frame_width = width;
    r.frame_height = height;
    r.region_x = region.x;
    r.region_y = region.y;
    r.region_width = region.width;
    r.region_height = region.height;
    r.sample_index = pass.pass == ARBOR_RENDER_PASS_SUPERSAMPLE ? pass.sample_index : 0;
    return r;
}

// The whole frame for width 0; throws when the region is not in the frame.
Region checked_region(Region region, uint32_t width, uint32_t height)
{
    if (region.width == 0 || region.height == 0)
        region = {0, 0, width, height};
    if (region.x >= width || region.y >= height || region.width > width - region.x ||
        region.height > height - region.y)
        throw std::invalid_argument("the region to render lies outside the frame");
    return region;
}

} // namespace

bool renders_passes(const PluginInstance &renderer)
{
    return renderer.call("plugin.get_interface", renderer.get()->get_interface, ARBOR_INTERFACE_RENDERER_2) != nullptr;
}

RenderDevice render_device(const PluginInstance &renderer)
{
    RenderDevice device;
    const auto *table = static_cast<const arbor_render_device_v1 *>(
        renderer.call("plugin.get_interface", renderer.get()->get_interface, ARBOR_INTERFACE_RENDER_DEVICE));
    if (!table || table->struct_size < ARBOR_MIN_SIZE(arbor_render_device_v1) || !table->describe)
        return device;
    arbor_render_device d{};
    d.struct_size = sizeof d;
    if (const arbor_status status = renderer.call("render-device.describe", table->describe, &d); status != ARBOR_OK)
        throw PluginError(status, renderer.id() + " cannot say what it renders on: " + renderer.last_error());
    if (d.kind == ARBOR_DEVICE_CPU || d.kind == ARBOR_DEVICE_GPU || d.kind == ARBOR_DEVICE_SOFTWARE_GPU)
        device.kind = d.kind;
    if (d.name)
        device.name = std::string(d.name).substr(0, 200);
    return device;
}

void render_region(PluginInstance &renderer, const arbor_render_request &request, RenderedImage &frame,
                   Region region, const FramePass &pass, ProgressSink *progress, std::stop_token stop)
{
    region = checked_region(region, frame.width, frame.height);
    const std::size_t labels = request.transfer_functions->branch_count;
    // NaN: "not measured"; a renderer that measures visibility overwrites all.
    frame.label_visibility.assign(labels, std::numeric_limits<double>::quiet_NaN());
    Task task(progress, std::move(stop));
    if (renders_passes(renderer)) {
        const auto &table = renderer.interface<arbor_renderer_v2>(ARBOR_INTERFACE_RENDERER_2);
        const arbor_render_request_v2 r = pass_request(request, pass, frame.width, frame.height, region);
        arbor_image out{};
        out.struct_size = sizeof out;
        out.width = region.width;
        out.height = region.height;
        out.row_stride = 4 * static_cast<int64_t>(frame.width);
        out.rgba = frame.rgba.data() + (std::size_t{region.y} * frame.width + region.x) * 4;
        out.depth = frame.depth.empty() ? nullptr : frame.depth.data() + std::size_t{region.y} * frame.width + region.x;
        out.depth_stride = frame.width;
        out.label_visibility = frame.label_visibility.data();
        out.label_visibility_count = static_cast<uint32_t>(labels);
        renderer.check(renderer.call("renderer.render", table.render, &r, &out, task.get()), "rendering");
    } else {
        if (pass.pass == ARBOR_RENDER_PASS_SUPERSAMPLE)
            throw PluginError(ARBOR_ERROR_UNSUPPORTED, renderer.id() + " offers arbor.renderer/1 only: no supersampling");
        const auto &table = renderer.interface<arbor_renderer_v1>(ARBOR_INTERFACE_RENDERER);
        const bool whole = region.x == 0 && region.y == 0 && region.width == frame.width && region.height == frame.height;
        RenderedImage scratch;
        RenderedImage &target = whole ? frame : scratch;
        if (!whole) {
            scratch.width = frame.width;
            scratch.height = frame.height;
            scratch.rgba.assign(frame.rgba.size(), 0.0f);
            scratch.depth.assign(frame.depth.size(), std::numeric_limits<float>::infinity());
        }
        arbor_image out{};
        out.struct_size = sizeof out;
        out.width = frame.width;
        out.height = frame.height;
        out.row_stride = 4 * static_cast<int64_t>(frame.width);
        out.rgba = target.rgba.data();
        out.depth = target.depth.empty() ? nullptr : target.depth.data();
        out.label_visibility = frame.label_visibility.data();
        out.label_visibility_count = static_cast<uint32_t>(labels);
        renderer.check(renderer.call("renderer.render", table.render, &request, &out, task.get()), "rendering");
        if (!whole)
            for (uint32_t y = region.y; y < region.y + region.height; ++y) {
                const std::size_t at = std::size_t{y} * frame.width + region.x;
                std::copy_n(scratch.rgba.begin() + static_cast<std::ptrdiff_t>(at * 4), std::size_t{region.width} * 4,
                            frame.rgba.begin() + static_cast<std::ptrdiff_t>(at * 4));
                if (!frame.depth.empty())
                    std::copy_n(scratch.depth.begin() + static_cast<std::ptrdiff_t>(at), region.width,
                                frame.depth.begin() + static_cast<std::ptrdiff_t>(at));
            }
    }
    check_region(renderer, frame, region, labels);
}

bool renders_into_gl(const PluginInstance &renderer)
{
    const auto *table = static_cast<const arbor_renderer_gl_v1 *>(
        renderer.call("plugin.get_interface", renderer.get()->get_interface, ARBOR_INTERFACE_RENDERER_GL));
    return table && table->struct_size >= ARBOR_MIN_SIZE(arbor_renderer_gl_v1) && table->render_gl &&
           table->release_gl && renders_passes(renderer);
}

void render_gl(PluginInstance &renderer, const arbor_render_request &request, const GlFrame &frame, Region region,
               const FramePass &pass, ProgressSink *progress, std::stop_token stop)
{
    region = checked_region(region, frame.width, frame.height);
    if (frame.texture == 0)
        throw std::invalid_argument("no texture to render into");
    const auto &table = renderer.interface<arbor_renderer_gl_v1>(ARBOR_INTERFACE_RENDERER_GL);
    const arbor_render_request_v2 r = pass_request(request, pass, frame.width, frame.height, region);
    arbor_gl_target target{};
    target.struct_size = sizeof target;
    target.texture = frame.texture;
    target.width = frame.width;
    target.height = frame.height;
    Task task(progress, std::move(stop));
    renderer.check(renderer.call("renderer-gl.render_gl", table.render_gl, &r, &target, task.get()),
                   "rendering into the OpenGL context");
}

void release_gl(PluginInstance &renderer)
{
    const auto &table = renderer.interface<arbor_renderer_gl_v1>(ARBOR_INTERFACE_RENDERER_GL);
    renderer.check(renderer.call("renderer-gl.release_gl", table.release_gl), "releasing its OpenGL objects");
}

RenderedImage render_image(PluginInstance &renderer, const arbor_render_request &request, uint32_t width,
                           uint32_t height, ProgressSink *progress, std::stop_token stop, const FramePass &pass)
{
    RenderedImage image;
    image.width = width;
    image.height = height;
    image.rgba.assign(std::size_t{width} * height * 4, 0.0f);
    image.depth.assign(std::size_t{width} * height, std::numeric_limits<float>::infinity());
    render_region(renderer, request, image, {}, pass, progress, std::move(stop));
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
    // Superior is up, tilted with the elevation.
    c.view_up[0] = -std::sin(az) * std::sin(el);
    c.view_up[1] = std::cos(az) * std::sin(el);
    c.view_up[2] = std::cos(el);
    // The camera's right: the view direction (-towards_camera) x up.
    const std::array<double, 3> right{-towards_camera[1] * c.view_up[2] + towards_camera[2] * c.view_up[1],
                                      -towards_camera[2] * c.view_up[0] + towards_camera[0] * c.view_up[2],
                                      -towards_camera[0] * c.view_up[1] + towards_camera[1] * c.view_up[0]};
    for (int a = 0; a < 3; ++a) {
        c.focal_point[a] = centre[a] + orbit.pan_right * right[a] + orbit.pan_up * c.view_up[a];
        c.position[a] = c.focal_point[a] + distance * towards_camera[a];
    }
    return c;
}

} // namespace arbor
