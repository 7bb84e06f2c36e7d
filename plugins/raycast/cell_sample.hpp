// cell_sample.hpp - what a sample reads from the cell of voxels it falls
// in: the trilinear value of its eight corners, its label resolved by that
// value when the corners' labels differ (LabelTree), and the gradient at
// the sample, trilinear between the corners' gradients, for shading and
// boundary emphasis.  The labels and gradients of the sample's position,
// not of its nearest voxel: surfaces and boundaries between structures
// come out smooth instead of as terraces and walls of voxel cubes.  The
// GLSL ray caster computes the same (resources/shaders/raycast.frag).
#pragma once

#include "voxel_grid.hpp"

#include <cmath>
#include <cstdint>

namespace arbor::raycast {

// Index offsets of a cell's corners from its lowest: (i, j, k), (i+1, j, k),
// (i, j+1, k), (i+1, j+1, k), then the same at k+1 (0 along an axis of one
// voxel).
struct CellCorners {
    int64_t at[8];
    explicit CellCorners(const VoxelGrid::Strides &s)
        : at{0, s.i, s.j, s.j + s.i, s.k, s.k + s.i, s.k + s.j, s.k + s.j + s.i}
    {
    }
};

struct Cell {
    float corner[8]; // the corners' values
    float fx, fy, fz; // the sample's place in the cell, [0, 1] each

    Cell(const VoxelGrid &g, std::size_t base, const CellCorners &c, float x, float y, float z) : fx(x), fy(y), fz(z)
    {
        const float *v = g.value.data() + base;
        for (int m = 0; m < 8; ++m)
            corner[m] = v[c.at[m]];
    }

    float value() const
    {
        const float c00 = corner[0] + fx * (corner[1] - corner[0]);
        const float c10 = corner[2] + fx * (corner[3] - corner[2]);
        const float c01 = corner[4] + fx * (corner[5] - corner[4]);
        const float c11 = corner[6] + fx * (corner[7] - corner[6]);
        const float c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
        return c0 + fz * (c1 - c0);
    }

    // A cell whose corners carry more than one label: the label of a
    // sample of `value` in it, from a lowest and a highest corner.
    uint32_t resolved_label(const VoxelGrid &g, std::size_t base, const CellCorners &c, float value) const
    {
        int low = 0, high = 0;
        for (int m = 1; m < 8; ++m) {
            if (corner[m] < corner[low])
                low = m;
            if (corner[m] > corner[high])
                high = m;
        }
        return g.tree.resolve(g.label[base + static_cast<std::size_t>(c.at[low])],
                              g.label[base + static_cast<std::size_t>(c.at[high])], value);
    }
};

// The gradient at a sample: the corners' gradients (unit direction times
// magnitude) weighted trilinearly.  `magnitude` is the trilinear magnitude
// on boundary emphasis' 8-bit scale, [0, 255]; `normal` the unit direction
// of the summed gradient, all 0 where it vanishes (no direction to shade by).
struct SampleGradient {
    float normal[3];
    float magnitude;

    SampleGradient(const VoxelGrid &g, std::size_t base, const CellCorners &c, const Cell &cell)
    {
        const float gx = cell.fx, gy = cell.fy, gz = cell.fz;
        const float hx = 1.0f - gx, hy = 1.0f - gy, hz = 1.0f - gz;
        const float w[8] = {hx * hy * hz, gx * hy * hz, hx * gy * hz, gx * gy * hz,
                            hx * hy * gz, gx * hy * gz, hx * gy * gz, gx * gy * gz};
        const Surface *s = g.surface.data() + base;
        float x = 0, y = 0, z = 0, m = 0;
        for (int k = 0; k < 8; ++k) {
            const Surface &q = s[c.at[k]];
            m += w[k] * static_cast<float>(q.gradient);
            // The byte's magnitude, a quarter up: a gradient below the
            // byte's first step still has its direction.
            const float wm = w[k] * (static_cast<float>(q.gradient) + 0.25f);
            x += wm * static_cast<float>(q.normal[0]);
            y += wm * static_cast<float>(q.normal[1]);
            z += wm * static_cast<float>(q.normal[2]);
        }
        const float length = std::sqrt(x * x + y * y + z * z);
        const float unit = length > 0.0f ? 1.0f / length : 0.0f;
        normal[0] = x * unit;
        normal[1] = y * unit;
        normal[2] = z * unit;
        magnitude = m;
    }
};

} // namespace arbor::raycast
