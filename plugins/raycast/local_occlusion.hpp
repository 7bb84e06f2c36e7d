// local_occlusion.hpp - local ambient occlusion by short rays, as VolView's
// "cinematic" mode does (vtk-js computeLAO, after Hernell, Ljung and
// Ynnerman's local ambient occlusion): at a sample that shows, a few short
// rays into the half-space the surface faces the viewer from measure how
// much of it is filled with opacity; crevices, folds and the insides of
// cavities darken, so shape reads without a light that casts shadows.
//
// The rays go along 14 fixed directions (the axes and the diagonals, in
// millimetres), those on the sample's side weighted by their cosine to the
// normal, each kSteps steps of kStepVoxels of the smallest spacing; a
// step's opacity comes from its own lookup tables (corrected for that
// length) with boundary emphasis, at the label of its cell's lowest voxel.
// The visibility found is clamped to [kFloor, 1]: no sample goes black.
// The GLSL ray caster walks the same rays (resources/shaders/raycast.frag).
#pragma once

#include "cell_sample.hpp"
#include "classification.hpp"

#include <array>

namespace arbor::raycast {

class LocalOcclusion {
public:
    static constexpr int kDirections = 14, kSteps = 4;
    static constexpr double kStepVoxels = 2.0;
    static constexpr float kFloor = 0.3f;
    // Samples contributing less than this to their pixel are not occluded
    // (their rays would cost without changing the picture).
    static constexpr float kContribution = 0.01f;

    // For a volume and its transfer functions: the directions in voxel
    // steps and the step's lookup tables.
    void build(const VoxelGrid &g, const arbor_tf_set &tf);

    // The visible share of the half-space around voxel position p
    // (voxel index coordinates) on the side of unit world normal n, in
    // [kFloor, 1].  The rays' steps start `jitter` (the ray's own start
    // offset, [0, 1)) of a step early: a fixed kernel on a lattice of
    // samples would draw moire on thick slices, a jittered one noise that
    // supersampling averages.
    float visibility(const VoxelGrid &g, const BoundaryEmphasis &boundaries, const double p[3], const float n[3],
                     float jitter) const;

    // For the GLSL ray caster: per direction, the unit vector in mm and
    // one step in voxel coordinates; and the step's tables.
    const std::array<std::array<float, 3>, kDirections> &world() const { return world_; }
    const std::array<std::array<float, 3>, kDirections> &steps() const { return steps_; }
    const ClassTable &table() const { return table_; }

private:
    std::array<std::array<float, 3>, kDirections> world_{}, steps_{};
    ClassTable table_;
};

} // namespace arbor::raycast
