// voxel_grid.hpp - the volume as the ray caster samples it: values as floats
// (any voxel type, any strides), labels per voxel with the cells where
// they differ and the labels' tree, unit gradient directions and gradient
// magnitudes per voxel for shading and boundary emphasis, and the map
// between LPS millimetres and voxel indices.  Rebuilt only when the
// request's revisions or pointers change.
#pragma once

#include "label_tree.hpp"
#include "unset_vector.hpp"

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

// Labels per voxel in the fewest bytes that hold the largest: a cut keeps
// tens of branches, so one byte a voxel instead of four (a 512 x 512 x 2000
// CT: 0.5 GB instead of 2.1).  Each voxel's word also says whether the
// cell it is the lowest corner of has corners of other labels (bit 0):
// a sample in a cell of one label reads one word, only a sample in a mixed
// cell reads its eight corners' labels.
class LabelGrid {
public:
    bool empty() const { return width_ == 0; }
    std::size_t size() const { return size_; }
    // Asks for the cache line of voxel v's word (a ray reading ahead of itself).
    void prefetch(std::size_t v) const
    {
        __builtin_prefetch(width_ == 1 ? static_cast<const void *>(narrow_.data() + v)
                           : width_ == 2 ? static_cast<const void *>(medium_.data() + v)
                                         : static_cast<const void *>(wide_.data() + v));
    }
    // label << 1 | (the cell at v is mixed)
    uint32_t word(std::size_t v) const
    {
        return width_ == 1 ? uint32_t{narrow_[v]} : width_ == 2 ? uint32_t{medium_[v]} : wide_[v];
    }
    uint32_t operator[](std::size_t v) const { return word(v) >> 1; }
    // Copies the labels of a grid of dims[0] x dims[1] x dims[2] voxels
    // (i fastest), whose largest is `max_label` (below 2^31), and marks the
    // mixed cells.  On all cores.
    void assign(const uint32_t *labels, const std::array<int64_t, 3> &dims, uint32_t max_label);
    void clear();

private:
    void set(std::size_t v, uint32_t word)
    {
        if (width_ == 1)
            narrow_[v] = static_cast<uint8_t>(word);
        else if (width_ == 2)
            medium_[v] = static_cast<uint16_t>(word);
        else
            wide_[v] = word;
    }
    static int width_for(uint32_t max_label); // bytes per word
    int width_ = 0; // 0: no labels
    std::size_t size_ = 0;
    UnsetVector<uint8_t> narrow_;
    UnsetVector<uint16_t> medium_;
    UnsetVector<uint32_t> wide_;
};

// What a voxel holds for shading besides its label, in one word (one cache
// line): the unit world gradient * 127, 0 where the field is flat, and the
// gradient magnitude, 255 at the field's 99.5th percentile and above
// (boundary emphasis).  A sample weighs its cell's eight (SampleGradient).
struct Surface {
    int8_t normal[3];
    uint8_t gradient;
};
static_assert(sizeof(Surface) == 4);

struct VoxelGrid {
    int64_t nx = 0, ny = 0, nz = 0;
    UnsetVector<float> value; // i fastest
    LabelGrid label;          // empty: every voxel has label 0
    uint32_t max_label = 0;
    LabelTree tree;           // how the labels nest; empty: nearest-voxel labels
    UnsetVector<Surface> surface; // per voxel
    Vec3 origin{};               // LPS of voxel (0, 0, 0)
    Mat3 to_world{};             // voxel index offsets -> LPS mm (direction * spacing)
    Mat3 to_voxel{};             // its inverse
    double min_spacing = 1.0;
    // Gradient magnitude (per mm) -> the 8-bit scale of Surface::gradient,
    // and the magnitude below which the field counts as flat.
    float gradient_scale = 1.0f, flat_gradient = 0.0f;
    // Slices at least twice as far apart as the finest spacing: a central
    // difference at the voxels would span two slice gaps, so a sample's
    // gradient is the one it would have on the volume resampled to
    // isotropic voxels (IsotropicGradient).
    bool thick_slices = false;
    // Per axis: this axis' spacing over the finest on an axis of thick
    // slices, else 1: how many voxels of the finest spacing a cell spans
    // along it (IsotropicGradient).
    float resample_scale[3] = {1.0f, 1.0f, 1.0f};

    std::size_t index(int64_t i, int64_t j, int64_t k) const { return static_cast<std::size_t>(i + nx * (j + ny * k)); }
    // Index offsets from a voxel to the next along i, j and k: a cell's
    // corners (0 along an axis of one voxel, whose cells are flat).
    struct Strides {
        int64_t i, j, k;
    };
    Strides strides() const { return {nx > 1 ? 1 : 0, ny > 1 ? nx : 0, nz > 1 ? nx * ny : 0}; }
};

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
