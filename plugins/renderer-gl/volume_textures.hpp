// volume_textures.hpp - what the ray casting shader samples, as textures:
// the voxel values (trilinear), labels (with their mixed-cell bits) and
// the labels' tree, normals with gradient magnitudes,
// the empty-block flags, and the classification tables (per label a row of
// premultiplied, opacity-corrected RGBA; the value ranges; the boundary
// factors and specular highlights).  All built by the shared ray casting
// core (plugins/raycast), so both ray casters classify alike.
#pragma once

#include "gl_objects.hpp"

#include <classification.hpp>
#include <local_occlusion.hpp>
#include <optical_model.hpp>
#include <voxel_grid.hpp>

namespace arbor::glraycast {

// Texture units the shader's samplers read.
namespace unit {
enum Unit : GLint { values = 0, labels, normals, blocks, lut, ranges, factors, occlusion, tree, refined };
} // namespace unit

class VolumeTextures {
public:
    // Values and normals of a new volume; throws std::runtime_error when
    // the device cannot hold it.
    void upload_volume(const raycast::VoxelGrid &g);
    void upload_labels(const raycast::VoxelGrid &g);
    void upload_blocks(const raycast::Occupancy &occupancy);
    // The lookup tables of each step: the full pass's and the coarse
    // pass's, each also for the refined step of mixed cells, and the local
    // ambient occlusion's rays'.
    struct Tables {
        const raycast::ClassTable &full, &coarse, &full_refined, &coarse_refined;
    };
    void upload_tables(const Tables &tables, const raycast::LocalOcclusion &occlusion,
                       const raycast::BoundaryEmphasis &boundaries, const raycast::Shading &shading);

    // Binds every texture to its unit; the coarse pass's lookup tables
    // when `coarse`.
    void bind(bool coarse) const;
    bool labelled() const { return labelled_; }
    // Labelled, with the labels' tree: samples can resolve their labels.
    bool resolvable() const { return resolvable_; }

private:
    Texture values_, labels_, normals_, blocks_, lut_, coarse_lut_, refined_lut_, coarse_refined_lut_, ranges_,
        factors_, occlusion_lut_, tree_;
    bool labelled_ = false, resolvable_ = false;
};

} // namespace arbor::glraycast
