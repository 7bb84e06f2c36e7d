// ray_geometry.hpp - where a ray caster's rays go: the camera's ray through
// a frame position, the per-pixel start offsets along a ray (jitter) and the
// offsets within a pixel for supersampling.  Both ray casters use these, so
// their pixels see the same rays.
#pragma once

#include "voxel_grid.hpp"

#include <arbor/renderer.h>

#include <cmath>
#include <cstdint>

namespace arbor::raycast {

struct Ray {
    Vec3 origin, direction; // LPS mm; direction unit length
};

// Pixel (x, y) -> ray, row 0 at the top.
class Camera {
public:
    Camera(const arbor_camera &c, uint32_t width, uint32_t height) : c_(c)
    {
        f_ = normalize({c.focal_point[0] - c.position[0], c.focal_point[1] - c.position[1],
                        c.focal_point[2] - c.position[2]});
        r_ = normalize(cross(f_, {c.view_up[0], c.view_up[1], c.view_up[2]}));
        if (!(std::hypot(r_[0], r_[1], r_[2]) > 0.5)) // view-up along the view direction
            r_ = normalize(cross(f_, std::fabs(f_[2]) < 0.9 ? Vec3{0, 0, 1} : Vec3{0, 1, 0}));
        u_ = cross(r_, f_);
        aspect_ = static_cast<double>(width) / height;
        width_ = width;
        height_ = height;
        half_ = c.projection == ARBOR_PROJECTION_PERSPECTIVE ? std::tan(c.view_angle * M_PI / 360.0) : c.parallel_scale;
    }

    // The ray through frame position (px, py) in pixels: pixel (x, y)
    // spans [x, x + 1) x [y, y + 1), its centre is (x + 0.5, y + 0.5).
    Ray ray(double px, double py) const
    {
        const double sx = (2.0 * px / width_ - 1.0) * aspect_ * half_;
        const double sy = (1.0 - 2.0 * py / height_) * half_;
        const Vec3 p{c_.position[0], c_.position[1], c_.position[2]};
        if (perspective())
            return {p, normalize({f_[0] + sx * r_[0] + sy * u_[0], f_[1] + sx * r_[1] + sy * u_[1],
                                  f_[2] + sx * r_[2] + sy * u_[2]})};
        return {{p[0] + sx * r_[0] + sy * u_[0], p[1] + sx * r_[1] + sy * u_[1], p[2] + sx * r_[2] + sy * u_[2]}, f_};
    }

    bool perspective() const { return c_.projection == ARBOR_PROJECTION_PERSPECTIVE; }
    const Vec3 &forward() const { return f_; }
    const Vec3 &right() const { return r_; }
    const Vec3 &up() const { return u_; }
    Vec3 position() const { return {c_.position[0], c_.position[1], c_.position[2]}; }
    // Half the image plane's height at unit distance (perspective) or in mm.
    double half_height() const { return half_; }
    double aspect() const { return aspect_; }

    static Vec3 cross(const Vec3 &a, const Vec3 &b)
    {
        return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }
    static Vec3 normalize(const Vec3 &v)
    {
        const double l = std::hypot(v[0], v[1], v[2]);
        return l > 0 ? Vec3{v[0] / l, v[1] / l, v[2] / l} : v;
    }

private:
    arbor_camera c_;
    Vec3 f_{}, r_{}, u_{};
    double aspect_ = 1, half_ = 1;
    uint32_t width_ = 1, height_ = 1;
};

// The R2 sequence (Roberts): well spread offsets within a pixel for the
// supersample passes.
inline std::array<double, 2> subpixel(uint32_t n)
{
    constexpr double g = 1.32471795724474602596, a1 = 1.0 / g, a2 = 1.0 / (g * g);
    return {std::fmod(0.5 + a1 * n, 1.0), std::fmod(0.5 + a2 * n, 1.0)};
}

// A fixed pseudo-random number in [0, 1) per pixel (integer hash); the
// GLSL ray caster computes the same.
inline double pixel_hash(uint32_t x, uint32_t y)
{
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return (h & 0xffffff) / 16777216.0;
}

// The golden-ratio step by which each supersample moves a ray's start.
constexpr double kSupersampleShift = 0.61803398874989485;

// The fraction of a step the ray of frame pixel (x, y) starts at: fixed
// per pixel (noise, not rings), moved on by each supersample.
inline double ray_offset(bool jitter, uint32_t sample_index, uint32_t x, uint32_t y)
{
    if (!jitter)
        return 0.0;
    const double h = pixel_hash(x, y);
    return sample_index ? std::fmod(h + kSupersampleShift * sample_index, 1.0) : h;
}

inline int64_t depth_stride_of(const arbor_image &out)
{
    return ARBOR_HAS_FIELD(arbor_image, out.struct_size, depth_stride) && out.depth_stride > 0
               ? out.depth_stride
               : static_cast<int64_t>(out.width);
}

} // namespace arbor::raycast
