#include "optical_model.hpp"

namespace arbor::raycast {

std::vector<sdk::ParamSpec> optical_model_params()
{
    return {sdk::ParamSpec::real("sample-distance", "Sample distance", 0.5, 0.01, 10.0)
                .unit("voxels")
                .hint("Distance between samples along a ray, in units of the smallest voxel spacing"),
            sdk::ParamSpec::boolean("sample-labels", "Labels per sample", true)
                .hint("A sample in a cell whose voxels belong to different structures takes the structure its "
                      "interpolated value lies in, so boundaries between structures are smooth isosurfaces "
                      "at their saddle values (topology-controlled volume rendering); off: its nearest voxel's"),
            sdk::ParamSpec::boolean("sample-gradients", "Gradients per sample", true)
                .hint("Shade and emphasise boundaries by the gradient at each sample, trilinear between the "
                      "voxels' gradients, so surfaces are smooth; off: the nearest voxel's (voxel facets)"),
            sdk::ParamSpec::boolean("shading", "Shading", true)
                .hint("Blinn-Phong shading from the gradient, lit from the camera"),
            sdk::ParamSpec::real("ambient", "Ambient", 0.3, 0.0, 1.0).group("Shading"),
            sdk::ParamSpec::real("diffuse", "Diffuse", 0.7, 0.0, 1.0).group("Shading"),
            sdk::ParamSpec::real("specular", "Specular", 0.25, 0.0, 1.0).group("Shading"),
            sdk::ParamSpec::real("shininess", "Shininess", 24.0, 1.0, 256.0).group("Shading"),
            sdk::ParamSpec::real("ambient-occlusion", "Ambient occlusion", 0.0, 0.0, 1.0)
                .group("Shading")
                .hint("Local ambient occlusion: short rays from each visible sample measure how much of the "
                      "space on its side is filled with opacity, and darken it by that much (to at most 70 %): "
                      "crevices and folds read without shadows; 0 turns it off"),
            sdk::ParamSpec::real("boundary-emphasis", "Boundary emphasis", 0.8, 0.0, 1.0)
                .hint("Scale opacity by the steepness of the field (gradient magnitude), so structures read "
                      "as surfaces and homogeneous interiors thin out; 0 turns it off"),
            sdk::ParamSpec::real("termination", "Early termination opacity", 0.99, 0.5, 1.0)
                .hint("A ray stops once its accumulated opacity reaches this"),
            sdk::ParamSpec::boolean("jitter", "Jitter", true)
                .hint("Offset each ray's first sample by a per-pixel fraction of a step: noise instead "
                      "of wood-grain rings"),
            sdk::ParamSpec::real("coarse-rate", "Coarse frame rate", 24.0, 1.0, 240.0)
                .unit("frames/s")
                .group("Interaction")
                .hint("The coarse pass (while the user drags) chooses how many pixels share a ray, from "
                      "2 x 2 to 8 x 8 in steps of half a pixel, to reach this rate, from the time its last "
                      "whole frames took"),
            sdk::ParamSpec::integer("coarse-pixels", "Coarse pixels per ray", 0, 0, 16)
                .group("Interaction")
                .hint("A fixed n: one coarse ray per n x n pixels; 0 chooses n from the coarse frame rate")};
}

Shading Shading::from(const sdk::ParamSet &params)
{
    Shading s;
    s.enabled = params.flag("shading");
    s.ambient = static_cast<float>(params.number("ambient"));
    s.diffuse = static_cast<float>(params.number("diffuse"));
    s.tabulate(static_cast<float>(params.number("specular")), static_cast<float>(params.number("shininess")));
    return s;
}

double CoarseRate::pixels_for(const arbor_render_request_v2 &request, double frames_per_second, double fixed)
{
    if (fixed > 0)
               return fixed;
    if (request.region_x == 0 && request.region_y == 0 && frame_pixels_ > 0) {
               adapt(frame_seconds_ * request.frame_width * request.frame_height / frame_pixels_, 1.0 / frames_per_second);
               frame_seconds_ = frame_pixels_ = 0;
    }
    return pixels_;
}

void CoarseRate::rendered(double seconds, double pixels)
{
    frame_seconds_ += seconds;
    frame_pixels_ += pixels;
}

// After a coarse frame that took `seconds`: the fewest pixels per ray whose
// frames are predicted to take at most `budget` (a frame's time goes with
// its rays, 1 / n^2).
void CoarseRate::adapt(double seconds, double budget)
{
    const double n = pixels_;
    seconds_ = seconds_ > 0 ? 0.5 * seconds_ + 0.5 * seconds : seconds;
    const double per_ray_area = seconds_ * n * n; // the frame's time at one ray per pixel
    double next = kCoarseMax;
    for (double m = kCoarseMin; m <= kCoarseMax; m += kCoarseStepBy)
               if (per_ray_area / (m * m) <= budget) {
                   next = m;
                   break;
               }
    if (next != pixels_) {
               seconds_ *= (n * n) / (next * next);
               pixels_ = next;
    }
}

} // namespace arbor::raycast
