// rendering.hpp - rendering through a renderer plugin into a host-owned
// image, and the orbit camera the CLI and GUI share.
#pragma once

#include "plugin_instance.hpp"

#include "core/rendered_image.hpp"
#include "core/volume.hpp"

#include <arbor/renderer.h>


namespace arbor {

RenderedImage render_image(PluginInstance &renderer, const arbor_render_request &request, uint32_t width,
                           uint32_t height, ProgressSink *progress = nullptr, std::stop_token stop = {});

// A camera orbiting the volume's centre.  Azimuth 0, elevation 0 looks at
// the patient's face (from anterior, superior up); azimuth turns towards the
// patient's left, elevation raises the camera towards superior.  Zoom 1
// fits the whole volume in view.
struct Orbit {
    double azimuth = 0.0, elevation = 0.0, zoom = 1.0;
    bool perspective = true;
    double view_angle = 30.0; // degrees
    bool operator==(const Orbit &) const = default;
};

arbor_camera orbit_camera(const Geometry &geometry, const Orbit &orbit);

} // namespace arbor
