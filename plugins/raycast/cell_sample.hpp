// cell_sample.hpp - what a sample reads from the cell of voxels it falls
// in: the trilinear value of its eight corners, its label resolved by that
// value when the corners' labels differ (LabelTree), and the gradient at
// the sample (trilinear between the corners' gradients, or on thick slices
// as on the volume resampled to isotropic voxels), for shading and
// boundary emphasis.  The labels and
// gradients of the sample's position, not of its nearest voxel: surfaces
// and boundaries between structures come out smooth instead of as
// terraces and walls of voxel cubes.  The GLSL ray caster computes the
// same (resources/shaders/raycast.frag).
#pragma once

#include "voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace arbor::raycast {

// Index offset of corner m of a cell from its lowest voxel: bit 0 of m
// along i, bit 1 along j, bit 2 along k (VoxelGrid::strides: 0 along an
// axis of one voxel).
inline int64_t corner_offset(const VoxelGrid::Strides &s, int m)
{
    return (m & 1 ? s.i : 0) + (m & 2 ? s.j : 0) + (m & 4 ? s.k : 0);
}

// 1 / sqrt(x) for x > 0 (0 for x <= 0): with SSE an estimate and one
// Newton step (relative error about 1e-7), not a square root and a division
// (the divider was a bottleneck of the shaded sample).
[[gnu::always_inline]] inline float inverse_sqrt(float x)
{
    if (!(x > 0.0f))
        return 0.0f;
#if defined(__SSE2__)
    const float y = _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
    return y * (1.5f - 0.5f * x * y * y);
#else
    return 1.0f / std::sqrt(x);
#endif
}

struct Cell {
    float corner[8]; // the corners' values, corner m as corner_offset
    float fx, fy, fz; // the sample's place in the cell, [0, 1] each

    // The cell whose lowest voxel is `base`.
    Cell(const VoxelGrid &g, std::size_t base, const VoxelGrid::Strides &s, float x, float y, float z)
        : fx(x), fy(y), fz(z)
    {
        const float *v = g.value.data() + base;
        corner[0] = v[0];
        corner[1] = v[s.i];
        corner[2] = v[s.j];
        corner[3] = v[s.j + s.i];
        corner[4] = v[s.k];
        corner[5] = v[s.k + s.i];
        corner[6] = v[s.k + s.j];
        corner[7] = v[s.k + s.j + s.i];
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
    // sample of `value` in it, from a lowest and a highest corner.  Static,
    // reading the corners again: a Cell whose address a call out of line
    // takes lives on the stack, and every sample (not just the rare ones
    // that get here) stored its corners there and loaded them back.
    [[gnu::noinline]] static uint32_t resolved_label(const VoxelGrid &g, std::size_t base, const VoxelGrid::Strides &s,
                                                     float value)
    {
        const Ends ends = extremes(g, base, s);
        return g.tree.resolve(ends.low, ends.high, value);
    }

    // The labels of a lowest and a highest corner of the cell at `base`:
    // a sample of any value in it resolves from them (LabelTree::resolve).
    struct Ends {
        uint32_t low, high;
    };
    static Ends extremes(const VoxelGrid &g, std::size_t base, const VoxelGrid::Strides &s)
    {
        const float *v = g.value.data() + base;
        int64_t low = 0, high = 0;
        for (int m = 1; m < 8; ++m) {
            const int64_t at = corner_offset(s, m);
            if (v[at] < v[low])
                low = at;
            if (v[at] > v[high])
                high = at;
        }
        return {g.label[base + static_cast<std::size_t>(low)], g.label[base + static_cast<std::size_t>(high)]};
    }
};

// The gradient at a sample: the corners' gradients (unit direction times
// magnitude) weighted trilinearly.  `magnitude` is the trilinear magnitude
// on boundary emphasis' 8-bit scale, [0, 255]; `normal` the unit direction
// of the summed gradient, all 0 where it vanishes (no direction to shade by).
// With SSE2 the eight corners are weighed four at a time (a shaded frame
// spent half its time here in scalar code: 32 conversions and 36 products a
// sample); `scalar` computes the same one corner at a time.
struct SampleGradient {
    float normal[3];
    float magnitude;
    // normal = direction * inverse_length (0 where the gradient vanishes):
    // a caller that needs only n . l takes (direction . l) * inverse_length
    // (one product after the square root's estimate, not three before it).
    float direction[3];
    float inverse_length;

    [[gnu::always_inline]] SampleGradient(const VoxelGrid &g, std::size_t base, const VoxelGrid::Strides &c,
                                          const Cell &cell)
    {
#if defined(__SSE2__)
        weigh_sse2(g.surface.data() + base, c, cell);
#else
        weigh_scalar(g.surface.data() + base, c, cell);
#endif
    }

    struct Scalar {};
    SampleGradient(Scalar, const VoxelGrid &g, std::size_t base, const VoxelGrid::Strides &c, const Cell &cell)
    {
        weigh_scalar(g.surface.data() + base, c, cell);
    }

private:
    // The byte's magnitude is taken a quarter up for the direction: a
    // gradient below the byte's first step still has its direction.
    static constexpr float kDirectionFloor = 0.25f;

    void weigh_scalar(const Surface *s, const VoxelGrid::Strides &c, const Cell &cell)
    {
        const float gx = cell.fx, gy = cell.fy, gz = cell.fz;
        const float hx = 1.0f - gx, hy = 1.0f - gy, hz = 1.0f - gz;
        const float w[8] = {hx * hy * hz, gx * hy * hz, hx * gy * hz, gx * gy * hz,
                            hx * hy * gz, gx * hy * gz, hx * gy * gz, gx * gy * gz};
        float x = 0, y = 0, z = 0, m = 0;
        for (int k = 0; k < 8; ++k) {
            const Surface &q = s[corner_offset(c, k)];
            m += w[k] * static_cast<float>(q.gradient);
            const float wm = w[k] * (static_cast<float>(q.gradient) + kDirectionFloor);
            x += wm * static_cast<float>(q.normal[0]);
            y += wm * static_cast<float>(q.normal[1]);
            z += wm * static_cast<float>(q.normal[2]);
        }
        finish(x, y, z, m);
    }

#if defined(__SSE2__)
    static __m128i words(const Surface *s, int64_t a, int64_t b, int64_t c, int64_t d)
    {
        // Four word loads into lanes (movd, unpack): not four stores and
        // one wide load, which store forwarding cannot serve.
        const auto word = [s](int64_t at) {
            int32_t w;
            std::memcpy(&w, s + at, 4);
            return _mm_cvtsi32_si128(w);
        };
        return _mm_unpacklo_epi64(_mm_unpacklo_epi32(word(a), word(b)), _mm_unpacklo_epi32(word(c), word(d)));
    }

    [[gnu::always_inline]] void weigh_sse2(const Surface *s, const VoxelGrid::Strides &c, const Cell &cell)
    {
        // Corners 0-3 (the k face) and 4-7 (the k + 1 face), each word
        // normal[0..2] in bytes 0-2 (signed), the magnitude in byte 3.
        const __m128i low = words(s, 0, c.i, c.j, c.j + c.i);
        const __m128i high = words(s, c.k, c.k + c.i, c.k + c.j, c.k + c.j + c.i);
        const float gx = cell.fx, gy = cell.fy, hx = 1.0f - gx, hy = 1.0f - gy;
        const __m128 wxy = _mm_setr_ps(hx * hy, gx * hy, hx * gy, gx * gy);
        const __m128 wl = _mm_mul_ps(wxy, _mm_set1_ps(1.0f - cell.fz)), wh = _mm_mul_ps(wxy, _mm_set1_ps(cell.fz));
        const auto field = [](__m128i v, int shift) {
            return _mm_cvtepi32_ps(_mm_srai_epi32(_mm_slli_epi32(v, shift), 24));
        };
        const __m128 ml = _mm_cvtepi32_ps(_mm_srli_epi32(low, 24)), mh = _mm_cvtepi32_ps(_mm_srli_epi32(high, 24));
        const __m128 floor = _mm_set1_ps(kDirectionFloor);
        const __m128 dl = _mm_mul_ps(wl, _mm_add_ps(ml, floor)), dh = _mm_mul_ps(wh, _mm_add_ps(mh, floor));
        __m128 x = _mm_add_ps(_mm_mul_ps(dl, field(low, 24)), _mm_mul_ps(dh, field(high, 24)));
        __m128 y = _mm_add_ps(_mm_mul_ps(dl, field(low, 16)), _mm_mul_ps(dh, field(high, 16)));
        __m128 z = _mm_add_ps(_mm_mul_ps(dl, field(low, 8)), _mm_mul_ps(dh, field(high, 8)));
        __m128 m = _mm_add_ps(_mm_mul_ps(wl, ml), _mm_mul_ps(wh, mh));
        _MM_TRANSPOSE4_PS(x, y, z, m);
        alignas(16) float sum[4];
        _mm_store_ps(sum, _mm_add_ps(_mm_add_ps(x, y), _mm_add_ps(z, m)));
        finish(sum[0], sum[1], sum[2], sum[3]);
    }
#endif

    [[gnu::always_inline]] void finish(float x, float y, float z, float m)
    {
        const float unit = inverse_sqrt(x * x + y * y + z * z);
        direction[0] = x, direction[1] = y, direction[2] = z;
        inverse_length = unit;
        normal[0] = x * unit;
        normal[1] = y * unit;
        normal[2] = z * unit;
        magnitude = m;
    }
};

// The gradient at a sample on thick slices: the one SampleGradient would
// give on the volume resampled to isotropic voxels at its finest spacing
// (trilinearly, so the same continuous field), from the values themselves
// (not rounded to the 8-bit words).
// Along an axis of even spacing it is SampleGradient's: the voxels' central
// differences weighted linearly.  Along a thick axis, in the part of a slab
// more than one fine spacing from both its slices, it is the slope between
// the two slices (the resampled voxels there lie on one straight line);
// within that distance of a slice it goes linearly over to the central
// difference at the slice, as the resampled voxels' differences do.  A
// central difference alone would span two slice gaps and blur a thin
// structure over both; the slope alone (the trilinear field's own
// derivative) is facetted at every cell face.  A sample reads the planes
// of voxels one before and one after its cell along each axis, as far as
// its weights need them.  (The field's own derivative along the rows and
// columns as well would cost nothing beyond the cell, but it is constant
// across each column of cells: fine stripes on a tumour MR of 0.78 mm
// rows, and 2 of the 18 anisotropic-fidelity rows under 35 dB.  This one
// costs the CT head's shaded frame about 1.4x: tests/bench/README.md.)
struct IsotropicGradient {
    float normal[3];
    float magnitude; // on Surface::gradient's 8-bit scale, [0, 255]
    float direction[3]; // normal = direction * inverse_length, as SampleGradient's
    float inverse_length;

    [[gnu::always_inline]] IsotropicGradient(const VoxelGrid &g, std::size_t base, const VoxelGrid::Strides &s,
                                             const int64_t cell[3], const float inverse[9], const Cell &c)
    {
        const float *v = g.value.data() + base;
        float d[3];
#if defined(__SSE2__)
        // Slices (thick k, even i and j), the sample's 4 x 4 columns inside
        // the volume: the common case, four columns at a time.
        if (g.resample_scale[0] == 1.0f && g.resample_scale[1] == 1.0f && cell[0] > 0 && cell[0] + 2 < g.nx &&
            cell[1] > 0 && cell[1] + 2 < g.ny) {
            across_slices_sse2(v, s, c, d);
            d[2] = along_slices(g, v, s, cell[2], c);
        } else
#endif
        {
            for (int a = 0; a < 3; ++a)
                d[a] = along(g, v, s, cell, c, a);
        }
        // Index-space derivatives to LPS by the inverse transpose.
        const float w[3] = {inverse[0] * d[0] + inverse[3] * d[1] + inverse[6] * d[2],
                            inverse[1] * d[0] + inverse[4] * d[1] + inverse[7] * d[2],
                            inverse[2] * d[0] + inverse[5] * d[1] + inverse[8] * d[2]};
        const float squared = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        const float inverse_length = inverse_sqrt(squared), length = squared * inverse_length;
        const float unit = length > g.flat_gradient ? inverse_length : 0.0f;
        this->inverse_length = unit;
        for (int a = 0; a < 3; ++a) {
            direction[a] = w[a];
            normal[a] = w[a] * unit;
        }
        magnitude = std::min(255.0f, length * g.gradient_scale);
    }

private:
    // The derivative along axis a in index units, v the cell's lowest voxel.
    [[gnu::noinline]] static float along(const VoxelGrid &g, const float *v, const VoxelGrid::Strides &s,
                                         const int64_t cell[3], const Cell &c, int a)
    {
        const int64_t stride[3] = {s.i, s.j, s.k}, size[3] = {g.nx, g.ny, g.nz};
        const float f[3] = {c.fx, c.fy, c.fz};
        // Across axis a: axes b and e.
        const int b = (a + 1) % 3, e = (a + 2) % 3;
        const int64_t sa = stride[a], sb = stride[b], se = stride[e];
        const float fb = f[b], fe = f[e], fa = f[a];
        // The cell's two faces across a, and the planes of voxels one
        // before and one after it, bilinear across a.
        const auto face = [&](int side) {
            const int m = side << a, mb = m | 1 << b, me = m | 1 << e;
            const float low = c.corner[m] + fb * (c.corner[mb] - c.corner[m]);
            const float high = c.corner[me] + fb * (c.corner[me | 1 << b] - c.corner[me]);
            return low + fe * (high - low);
        };
        const auto plane = [&](int64_t at) {
            const float *p = v + at;
            const float low = p[0] + fb * (p[sb] - p[0]), high = p[se] + fb * (p[se + sb] - p[se]);
            return low + fe * (high - low);
        };
        // The weights of the central differences at the two faces; the
        // slope between them has the rest (none on an even axis).
        const float scale = g.resample_scale[a];
        const float w0 = std::max(0.0f, 1.0f - fa * scale), w1 = std::max(0.0f, 1.0f - (1.0f - fa) * scale);
        const float p0 = face(0), p1 = face(1);
        float da = (1.0f - w0 - w1) * (p1 - p0);
        // At the volume's faces the difference is one-sided, as the
        // voxels' own (compute_normals).
        if (w0 > 0.0f) {
            const bool inner = cell[a] > 0;
            da += w0 * (inner ? 0.5f * (p1 - plane(-sa)) : p1 - p0);
        }
        if (w1 > 0.0f) {
            const bool inner = cell[a] + 2 < size[a];
            da += w1 * (inner ? 0.5f * (plane(2 * sa) - p0) : p1 - p0);
        }
        return da;
    }

    // along(…, 2) on an axis k of thick slices, the sample's columns inside
    // the volume: the faces from the cell's corners, the plane beyond one
    // only when the sample is within a fine spacing of it.
    [[gnu::always_inline]] static float along_slices(const VoxelGrid &g, const float *v, const VoxelGrid::Strides &s,
                                                     int64_t k, const Cell &c)
    {
        const float fx = c.fx, fy = c.fy, fz = c.fz, scale = g.resample_scale[2];
        const auto bilinear = [fx, fy](float a, float b, float e, float f) {
            const float low = a + fx * (b - a), high = e + fx * (f - e);
            return low + fy * (high - low);
        };
        const float *q = c.corner;
        const float p0 = bilinear(q[0], q[1], q[2], q[3]), p1 = bilinear(q[4], q[5], q[6], q[7]);
        const float w0 = std::max(0.0f, 1.0f - fz * scale), w1 = std::max(0.0f, 1.0f - (1.0f - fz) * scale);
        float d = (1.0f - w0 - w1) * (p1 - p0);
        if (w0 > 0.0f) {
            const float *p = v - s.k;
            d += w0 * (k > 0 ? 0.5f * (p1 - bilinear(p[0], p[s.i], p[s.j], p[s.j + s.i])) : p1 - p0);
        }
        if (w1 > 0.0f) {
            const float *p = v + 2 * s.k;
            d += w1 * (k + 2 < g.nz ? 0.5f * (bilinear(p[0], p[s.i], p[s.j], p[s.j + s.i]) - p0) : p1 - p0);
        }
        return d;
    }

#if defined(__SSE2__)
    // The derivatives along i and j (even axes: central differences
    // weighted linearly) from the 4 x 4 columns around the cell, i - 1 to
    // i + 2 and j - 1 to j + 2, in its two slices: eight loads of four.
    // Along i, the planes i - 1 .. i + 2 (the lanes) between rows j and
    // j + 1, taken (-(1 - fx), -fx, 1 - fx, fx) / 2; along j, the rows
    // j - 1 .. j + 2 taken so, between columns i and i + 1.
    [[gnu::always_inline]] static void across_slices_sse2(const float *v, const VoxelGrid::Strides &s, const Cell &c,
                                                          float d[3])
    {
        const float *first = v - s.j - 1;
        __m128 low[4], high[4]; // rows j - 1 .. j + 2 of the two slices
        for (int n = 0; n < 4; ++n) {
            low[n] = _mm_loadu_ps(first + n * s.j);
            high[n] = _mm_loadu_ps(first + n * s.j + s.k);
        }
        // Each term weighted at once (products side by side, then a tree
        // of sums: a short chain from the loads).
        const float fy = c.fy, fz = c.fz, hy = 1.0f - fy, hz = 1.0f - fz;
        const auto times = [](__m128 x, float w) { return _mm_mul_ps(x, _mm_set1_ps(w)); };
        const __m128 planes_i = _mm_add_ps(_mm_add_ps(times(low[1], hy * hz), times(low[2], fy * hz)),
                                           _mm_add_ps(times(high[1], hy * fz), times(high[2], fy * fz)));
        const float by = 0.5f * hy, gy = 0.5f * fy;
        const __m128 back = _mm_add_ps(_mm_add_ps(times(low[0], by * hz), times(low[1], gy * hz)),
                                       _mm_add_ps(times(high[0], by * fz), times(high[1], gy * fz)));
        const __m128 ahead = _mm_add_ps(_mm_add_ps(times(low[2], by * hz), times(low[3], gy * hz)),
                                        _mm_add_ps(times(high[2], by * fz), times(high[3], gy * fz)));
        const float gx = 0.5f * c.fx, bx = 0.5f - gx;
        const __m128 a = _mm_mul_ps(planes_i, _mm_setr_ps(-bx, -gx, bx, gx));
        const __m128 b = _mm_mul_ps(_mm_sub_ps(ahead, back), _mm_setr_ps(0.0f, 1.0f - c.fx, c.fx, 0.0f));
        // The two horizontal sums at once.
        const __m128 pairs = _mm_add_ps(_mm_unpacklo_ps(a, b), _mm_unpackhi_ps(a, b)); // a0+a2 b0+b2 a1+a3 b1+b3
        const __m128 sums = _mm_add_ps(pairs, _mm_movehl_ps(pairs, pairs));
        d[0] = _mm_cvtss_f32(sums);
        d[1] = _mm_cvtss_f32(_mm_shuffle_ps(sums, sums, 1));
    }
#endif
};

} // namespace arbor::raycast
