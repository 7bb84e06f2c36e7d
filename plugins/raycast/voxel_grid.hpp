// voxel_grid.hpp - the volume as the ray caster samples it: values as floats
// (any voxel type, any strides), labels per voxel, unit gradient directions
// per voxel for shading, and the map between LPS millimetres and voxel
// indices.  Rebuilt only when the request's revisions or pointers change.
#pragma once

#include <arbor/renderer.h>
#include <arbor/sdk/task.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace arbor::raycast {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<double, 9>; // row-major

inline Vec3 mul(const Mat3 &m, const Vec3 &v)
{
    return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
            m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

struct VoxelGrid {
    int64_t nx = 0, ny = 0, nz = 0;
    std::vector<float> value;    // i fastest
    std::vector<uint32_t> label; // empty: every voxel has label 0
    uint32_t max_label = 0;
    std::vector<int8_t> normal;  // [3 * voxels]: unit world gradient * 127; 0 where the field is flat
    // Gradient magnitude per voxel, 255 at the field's 99.5th percentile (and above).
    std::vector<uint8_t> gradient;
    Vec3 origin{};               // LPS of voxel (0, 0, 0)
    Mat3 to_world{};             // voxel index offsets -> LPS mm (direction * spacing)
    Mat3 to_voxel{};             // its inverse
    double min_spacing = 1.0;

    std::size_t index(int64_t i, int64_t j, int64_t k) const { return static_cast<std::size_t>(i + nx * (j + ny * k)); }
};

// The grid at half resolution for the coarse pass: values averaged over
// 2 x 2 x 2 voxels, the label of the first, normals and gradients of its own.
void downsample(const VoxelGrid &g, VoxelGrid &half, const sdk::Task &task);

class VoxelGridCache {
public:
    // Brings the grid up to date (values and normals when the volume
    // changed, labels when they changed; a revision of 0 is "unknown":
    // rebuilt).  On all cores, cancellable.
    const VoxelGrid &update(const arbor_volume &volume, uint64_t volume_revision, const arbor_label_map *labels,
                            uint64_t labels_revision, const sdk::Task &task);
    // Changes whenever update changed the grid; values_generation() only
    // when the values (and normals) changed, not for new labels alone.
    uint64_t generation() const { return generation_; }
    uint64_t values_generation() const { return values_generation_; }

private:
    uint64_t generation_ = 0, values_generation_ = 0;
    VoxelGrid grid_;
    const void *voxels_ = nullptr, *labels_ = nullptr;
    uint64_t volume_revision_ = ~uint64_t{0}, labels_revision_ = ~uint64_t{0};
    std::array<int64_t, 3> dims_{};
};

} // namespace arbor::raycast
