#include "voxel_grid.hpp"
#include "cancellation.hpp"

#include <arbor/sdk/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace arbor::raycast {

namespace {

// Slabs of k on all cores; a cancelled task stops the slabs not yet begun.
template <class Body> void for_slabs(int64_t nz, const sdk::Task &task, const Body &body)
{
    Cancellation cancel(task);
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, nz), [&](const tbb::blocked_range<int64_t> &ks) {
        if (cancel.stopped())
            return;
        for (int64_t k = ks.begin(); k != ks.end(); ++k)
            body(k);
    });
    task.throw_if_cancelled();
}

template <class T>
void copy_values(const arbor_volume &v, std::vector<float> &out, const sdk::Task &task)
{
    const char *base = static_cast<const char *>(v.voxels);
    for_slabs(v.dims[2], task, [&](int64_t k) {
        std::size_t at = static_cast<std::size_t>(k * v.dims[0] * v.dims[1]);
        for (int64_t j = 0; j < v.dims[1]; ++j)
            for (int64_t i = 0; i < v.dims[0]; ++i) {
                T x;
                std::memcpy(&x, base + i * v.strides[0] + j * v.strides[1] + k * v.strides[2], sizeof x);
                out[at++] = static_cast<float>(x);
            }
    });
}

Mat3 inverse(const Mat3 &m)
{
    const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                       m[2] * (m[3] * m[7] - m[4] * m[6]);
    if (!(std::fabs(det) > 0))
        sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the volume's direction matrix is singular");
    const double s = 1.0 / det;
    return {(m[4] * m[8] - m[5] * m[7]) * s, (m[2] * m[7] - m[1] * m[8]) * s, (m[1] * m[5] - m[2] * m[4]) * s,
            (m[5] * m[6] - m[3] * m[8]) * s, (m[0] * m[8] - m[2] * m[6]) * s, (m[2] * m[3] - m[0] * m[5]) * s,
            (m[3] * m[7] - m[4] * m[6]) * s, (m[1] * m[6] - m[0] * m[7]) * s, (m[0] * m[4] - m[1] * m[3]) * s};
}

// Central differences in index space, taken to LPS by the inverse transpose
// of the grid's matrix, normalised.  Gradients far below the field's typical
// change per voxel count as flat (no shading there).  Their magnitudes are
// kept in 8 bits relative to the 99.5th percentile: what boundary-emphasis
// opacity needs.
void compute_normals(VoxelGrid &g, const sdk::Task &task)
{
    const auto [lo, hi] = std::minmax_element(g.value.begin(), g.value.end());
    const double flat = 1e-3 * (*hi - *lo) / g.min_spacing;
    g.normal.assign(3 * g.value.size(), 0);
    std::vector<float> magnitude(g.value.size(), 0.0f);
    const Mat3 &inv = g.to_voxel; // rows of M^-1 = columns of M^-T
    for_slabs(g.nz, task, [&](int64_t k) {
        for (int64_t j = 0; j < g.ny; ++j)
            for (int64_t i = 0; i < g.nx; ++i) {
                const auto diff = [&](int64_t a0, int64_t a1, int64_t b0, int64_t b1, int64_t c0, int64_t c1) {
                    return g.value[g.index(a1, b1, c1)] - g.value[g.index(a0, b0, c0)];
                };
                const int64_t i0 = std::max<int64_t>(i - 1, 0), i1 = std::min(i + 1, g.nx - 1);
                const int64_t j0 = std::max<int64_t>(j - 1, 0), j1 = std::min(j + 1, g.ny - 1);
                const int64_t k0 = std::max<int64_t>(k - 1, 0), k1 = std::min(k + 1, g.nz - 1);
                const Vec3 gv{i1 > i0 ? diff(i0, i1, j, j, k, k) / double(i1 - i0) : 0.0,
                              j1 > j0 ? diff(i, i, j0, j1, k, k) / double(j1 - j0) : 0.0,
                              k1 > k0 ? diff(i, i, j, j, k0, k1) / double(k1 - k0) : 0.0};
                const Vec3 gw{inv[0] * gv[0] + inv[3] * gv[1] + inv[6] * gv[2],
                              inv[1] * gv[0] + inv[4] * gv[1] + inv[7] * gv[2],
                              inv[2] * gv[0] + inv[5] * gv[1] + inv[8] * gv[2]};
                const double len = std::hypot(gw[0], gw[1], gw[2]);
                magnitude[g.index(i, j, k)] = static_cast<float>(len);
                if (len <= flat)
                    continue;
                int8_t *n = &g.normal[3 * g.index(i, j, k)];
                for (int c = 0; c < 3; ++c)
                    n[c] = static_cast<int8_t>(std::lround(127.0 * gw[c] / len));
            }
    });
    std::vector<float> sample;
    const std::size_t stride = std::max<std::size_t>(1, magnitude.size() / (1 << 20));
    for (std::size_t v = 0; v < magnitude.size(); v += stride)
        sample.push_back(magnitude[v]);
    const auto at = sample.begin() + static_cast<std::ptrdiff_t>(0.995 * (sample.size() - 1));
    std::nth_element(sample.begin(), at, sample.end());
    const float top = *at > 0 ? *at : 1.0f;
    g.gradient.resize(magnitude.size());
    const std::size_t slab = static_cast<std::size_t>(g.nx * g.ny);
    for_slabs(g.nz, task, [&](int64_t k) {
        for (std::size_t v = static_cast<std::size_t>(k) * slab; v < static_cast<std::size_t>(k + 1) * slab; ++v)
            g.gradient[v] = static_cast<uint8_t>(std::min(255.0f, std::round(255.0f * magnitude[v] / top)));
    });
}

} // namespace

void downsample(const VoxelGrid &g, VoxelGrid &half, const sdk::Task &task)
{
    half.nx = (g.nx + 1) / 2;
    half.ny = (g.ny + 1) / 2;
    half.nz = (g.nz + 1) / 2;
    const std::size_t n = static_cast<std::size_t>(half.nx * half.ny * half.nz);
    half.value.assign(n, 0.0f);
    half.label.assign(g.label.empty() ? 0 : n, 0u);
    half.max_label = g.max_label;
    for_slabs(half.nz, task, [&](int64_t k) {
        for (int64_t j = 0; j < half.ny; ++j)
            for (int64_t i = 0; i < half.nx; ++i) {
                float sum = 0;
                int count = 0;
                for (int64_t c = 2 * k; c <= std::min(2 * k + 1, g.nz - 1); ++c)
                    for (int64_t b = 2 * j; b <= std::min(2 * j + 1, g.ny - 1); ++b)
                        for (int64_t a = 2 * i; a <= std::min(2 * i + 1, g.nx - 1); ++a, ++count)
                            sum += g.value[g.index(a, b, c)];
                const std::size_t at = half.index(i, j, k);
                half.value[at] = sum / static_cast<float>(count);
                if (!g.label.empty())
                    half.label[at] = g.label[g.index(2 * i, 2 * j, 2 * k)];
            }
    });
    // Each half voxel sits at the centre of the 2 x 2 x 2 block it averages.
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
            half.to_world[3 * r + c] = 2.0 * g.to_world[3 * r + c];
        half.origin[r] = g.origin[r] + 0.5 * (g.to_world[3 * r] + g.to_world[3 * r + 1] + g.to_world[3 * r + 2]);
    }
    half.to_voxel = inverse(half.to_world);
    half.min_spacing = 2.0 * g.min_spacing;
    compute_normals(half, task);
}

const VoxelGrid &VoxelGridCache::update(const arbor_volume &v, uint64_t volume_revision,
                                        const arbor_label_map *label_map, uint64_t labels_revision,
                                        const sdk::Task &task)
{
    const std::array<int64_t, 3> dims{v.dims[0], v.dims[1], v.dims[2]};
    if (v.voxels != voxels_ || volume_revision != volume_revision_ || volume_revision == 0 || dims != dims_) {
        voxels_ = nullptr; // a cancelled rebuild leaves the grid stale
        ++generation_;
        ++values_generation_;
        VoxelGrid &g = grid_;
        g.nx = dims[0];
        g.ny = dims[1];
        g.nz = dims[2];
        g.value.resize(static_cast<std::size_t>(g.nx * g.ny * g.nz));
        switch (v.voxel_type) {
        case ARBOR_VOXEL_U8: copy_values<uint8_t>(v, g.value, task); break;
        case ARBOR_VOXEL_I8: copy_values<int8_t>(v, g.value, task); break;
        case ARBOR_VOXEL_U16: copy_values<uint16_t>(v, g.value, task); break;
        case ARBOR_VOXEL_I16: copy_values<int16_t>(v, g.value, task); break;
        case ARBOR_VOXEL_U32: copy_values<uint32_t>(v, g.value, task); break;
        case ARBOR_VOXEL_I32: copy_values<int32_t>(v, g.value, task); break;
        case ARBOR_VOXEL_F32: copy_values<float>(v, g.value, task); break;
        case ARBOR_VOXEL_F64: copy_values<double>(v, g.value, task); break;
        default: sdk::fail(ARBOR_ERROR_UNSUPPORTED, "unknown voxel type");
        }
        for (float x : g.value)
            if (!std::isfinite(x))
                sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the volume holds NaN or infinite values");
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                g.to_world[3 * r + c] = v.direction[3 * r + c] * v.spacing[c];
        g.to_voxel = inverse(g.to_world);
        g.origin = {v.origin[0], v.origin[1], v.origin[2]};
        g.min_spacing = std::min({v.spacing[0], v.spacing[1], v.spacing[2]});
        compute_normals(g, task);
        voxels_ = v.voxels;
        volume_revision_ = volume_revision;
        dims_ = dims;
        labels_ = nullptr; // labels are re-read for a new volume
    }
    const void *labels = label_map ? label_map->labels : nullptr;
    if (labels != labels_ || labels_revision != labels_revision_ || (labels && labels_revision == 0)) {
        ++generation_;
        grid_.max_label = 0;
        if (labels) {
            grid_.label.assign(label_map->labels, label_map->labels + grid_.value.size());
            grid_.max_label = *std::max_element(grid_.label.begin(), grid_.label.end());
        } else {
            grid_.label.clear();
        }
        labels_ = labels;
        labels_revision_ = labels_revision;
    }
    return grid_;
}

} // namespace arbor::raycast
