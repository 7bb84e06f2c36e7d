#include "framing.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::pipeline {

namespace {

constexpr float kSeen = 0.02f; // a pixel's opacity above which something is seen there

using V3 = std::array<double, 3>;

V3 sub(const double *a, const double *b)
{
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

V3 normalized(V3 v)
{
    const double l = std::hypot(v[0], v[1], v[2]);
    return l > 0 ? V3{v[0] / l, v[1] / l, v[2] / l} : v;
}

V3 cross(const V3 &a, const V3 &b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

} // namespace

std::optional<Framing> frame_content(const arbor_camera &camera, const RenderedImage &preview, uint32_t width,
                                     uint32_t height, double fill)
{
    const uint32_t pw = preview.width, ph = preview.height;
    uint32_t x0 = pw, x1 = 0, y0 = ph, y1 = 0;
    for (uint32_t y = 0; y < ph; ++y)
        for (uint32_t x = 0; x < pw; ++x)
            if (preview.rgba[(std::size_t{y} * pw + x) * 4 + 3] > kSeen) {
                x0 = std::min(x0, x);
                x1 = std::max(x1, x);
                y0 = std::min(y0, y);
                y1 = std::max(y1, y);
            }
    if (x0 > x1)
        return std::nullopt;
    // The content box as fractions of the image's width and height, and its
    // centre in normalised device coordinates ([-1, 1], y up).
    const double fx = (x1 - x0 + 1.0) / pw, fy = (y1 - y0 + 1.0) / ph;
    const double cx = (x0 + x1 + 1.0) / pw - 1.0, cy = 1.0 - (y0 + y1 + 1.0) / ph;
    const double w = width, h = height, shorter = std::min(w, h);
    Framing f;
    f.content_fraction = std::max(fx * w, fy * h) / shorter;
    f.scale = std::min({fill * shorter / std::max(fx * w, fy * h), fill / fx, fill / fy});

    // Pan: the content's centre to the image's, in the plane of the focal point.
    arbor_camera c = camera;
    const V3 forward = normalized(sub(c.focal_point, c.position));
    V3 right = normalized(cross(forward, {c.view_up[0], c.view_up[1], c.view_up[2]}));
    const V3 up = cross(right, forward);
    const double distance = std::hypot(c.focal_point[0] - c.position[0], c.focal_point[1] - c.position[1],
                                       c.focal_point[2] - c.position[2]);
    const double half_h = c.projection == ARBOR_PROJECTION_PERSPECTIVE
                              ? distance * std::tan(c.view_angle * M_PI / 360.0)
                              : c.parallel_scale;
    const double half_w = half_h * w / h;
    for (int a = 0; a < 3; ++a) {
        const double shift = cx * half_w * right[a] + cy * half_h * up[a];
        c.focal_point[a] += shift;
        c.position[a] += shift;
    }
    // Zoom: closer (perspective) or a smaller view (orthographic).
    if (c.projection == ARBOR_PROJECTION_PERSPECTIVE)
        for (int a = 0; a < 3; ++a)
            c.position[a] = c.focal_point[a] - forward[a] * distance / f.scale;
    else
        c.parallel_scale /= f.scale;
    f.camera = c;
    return f;
}

} // namespace arbor::pipeline
