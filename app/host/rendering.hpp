// rendering.hpp - rendering through a renderer plugin into a host-owned
// image, and the orbit camera the CLI and GUI share.
#pragma once

#include "plugin_instance.hpp"

#include "core/rendered_image.hpp"
#include "core/volume.hpp"

#include <arbor/renderer.h>


namespace arbor {

// Which pass of which frame: a renderer offering arbor.renderer/2 gets
// them as they are; one offering /1 alone renders FULL for COARSE, whole
// frames (the host copies the region out), and cannot SUPERSAMPLE.
struct FramePass {
    arbor_render_pass pass = ARBOR_RENDER_PASS_FULL;
    uint32_t sample_index = 0;                // SUPERSAMPLE: 1, 2, ...
    uint64_t transfer_functions_revision = 0; // 0: unknown (the renderer compares contents)
};

struct Region {
    uint32_t x = 0, y = 0, width = 0, height = 0; // width 0: the whole frame
};

// The whole frame, in one call.
RenderedImage render_image(PluginInstance &renderer, const arbor_render_request &request, uint32_t width,
                           uint32_t height, ProgressSink *progress = nullptr, std::stop_token stop = {},
                           const FramePass &pass = {});

// A region of `frame` (allocated by the caller: width x height, rgba and
// depth), rendered in place; frame.label_visibility becomes the region's.
// For SUPERSAMPLE the region must hold the previous pass.  Cancelled:
// throws, and each pixel of the region is as it was or final.
void render_region(PluginInstance &renderer, const arbor_render_request &request, RenderedImage &frame,
                   Region region, const FramePass &pass, ProgressSink *progress = nullptr, std::stop_token stop = {});

// Whether the renderer offers arbor.renderer/2 (tiles, coarse and
// supersample passes).
bool renders_passes(const PluginInstance &renderer);

// A texture of the OpenGL context current on the calling thread, made by
// the caller (GL_RGBA8, GL_RGBA16F or GL_RGBA32F, width x height: the
// frame), that a renderer offering arbor.renderer-gl/1 renders into.
struct GlFrame {
    uint32_t texture = 0;
    uint32_t width = 0, height = 0;
};

// Whether the renderer renders into the host's OpenGL context
// (arbor.renderer-gl/1, with /2; an isolated plugin never does).
bool renders_into_gl(const PluginInstance &renderer);

// A pass of a region of the frame into its texture, as render_region does
// into an image (no depth, no visibility).  Every call of one renderer
// comes with the same context current; release_gl with it current before
// the renderer is destroyed.
void render_gl(PluginInstance &renderer, const arbor_render_request &request, const GlFrame &frame, Region region,
               const FramePass &pass, ProgressSink *progress = nullptr, std::stop_token stop = {});
void release_gl(PluginInstance &renderer);

// What a renderer renders on (arbor.render-device/1); a renderer that does
// not offer it counts as rendering on the CPU.  Throws PluginError when the
// renderer cannot find out (an OpenGL renderer without a context).
struct RenderDevice {
    arbor_device_kind kind = ARBOR_DEVICE_CPU;
    std::string name; // "" when the renderer does not say
};
RenderDevice render_device(const PluginInstance &renderer);

// A camera orbiting the volume's centre.  Azimuth 0, elevation 0 looks at
// the patient's face (from anterior, superior up); azimuth turns towards the
// patient's left, elevation raises the camera towards superior.  Zoom 1
// fits the whole volume in view.
struct Orbit {
    double azimuth = 0.0, elevation = 0.0, zoom = 1.0;
    bool perspective = true;
    double view_angle = 30.0; // degrees
    // The focal point moved off the centre, in mm along the camera's right
    // and up directions (a pan, as a middle-button drag does in 3D Slicer).
    double pan_right = 0.0, pan_up = 0.0;
    bool operator==(const Orbit &) const = default;
};

arbor_camera orbit_camera(const Geometry &geometry, const Orbit &orbit);

} // namespace arbor
