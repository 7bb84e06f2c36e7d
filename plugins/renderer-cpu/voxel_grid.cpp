#include "voxel_grid.hpp"

#include <arbor/sdk/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace arbor::raycast {

namespace {

template <class T>
void copy_values(const arbor_volume &v, std::vector<float> &out)
{
    const char *base = static_cast<const char *>(v.voxels);
    std::size_t at = 0;
    for (int64_t k = 0; k < v.dims[2]; ++k)
        for (int64_t j = 0; j < v.dims[1]; ++j)
            for (int64_t i = 0; i < v.dims[0]; ++i) {
                T x;
                std::memcpy(&x, base + i * v.strides[0] + j * v.strides[1] + k * v.strides[2], sizeof x);
                out[at++] = static_cast<float>(x);
            }
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
    for (int64_t k = 0; k < g.nz; ++k) {
        if ((k & 15) == 0)
            task.throw_if_cancelled();
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
    }
    std::vector<float> sample;
    const std::size_t stride = std::max<std::size_t>(1, magnitude.size() / (1 << 20));
    for (std::size_t v = 0; v < magnitude.size(); v += stride)
        sample.push_back(magnitude[v]);
    const auto at = sample.begin() + static_cast<std::ptrdiff_t>(0.995 * (sample.size() - 1));
    std::nth_element(sample.begin(), at, sample.end());
    const float top = *at > 0 ? *at : 1.0f;
    g.gradient.resize(magnitude.size());
    for (std::size_t v = 0; v < magnitude.size(); ++v)
        g.gradient[v] = static_cast<uint8_t>(std::min(255.0f, std::round(255.0f * magnitude[v] / top)));
}

} // namespace

const VoxelGrid &VoxelGridCache::update(const arbor_render_request &request, const sdk::Task &task)
{
    const arbor_volume &v = *request.volume;
    const std::array<int64_t, 3> dims{v.dims[0], v.dims[1], v.dims[2]};
    if (v.voxels != voxels_ || request.volume_revision != volume_revision_ || dims != dims_) {
        VoxelGrid &g = grid_;
        g.nx = dims[0];
        g.ny = dims[1];
        g.nz = dims[2];
        g.value.resize(static_cast<std::size_t>(g.nx * g.ny * g.nz));
        switch (v.voxel_type) {
        case ARBOR_VOXEL_U8: copy_values<uint8_t>(v, g.value); break;
        case ARBOR_VOXEL_I8: copy_values<int8_t>(v, g.value); break;
        case ARBOR_VOXEL_U16: copy_values<uint16_t>(v, g.value); break;
        case ARBOR_VOXEL_I16: copy_values<int16_t>(v, g.value); break;
        case ARBOR_VOXEL_U32: copy_values<uint32_t>(v, g.value); break;
        case ARBOR_VOXEL_I32: copy_values<int32_t>(v, g.value); break;
        case ARBOR_VOXEL_F32: copy_values<float>(v, g.value); break;
        case ARBOR_VOXEL_F64: copy_values<double>(v, g.value); break;
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
        volume_revision_ = request.volume_revision;
        dims_ = dims;
        labels_ = nullptr; // labels are re-read for a new volume
    }
    const void *labels = request.labels ? request.labels->labels : nullptr;
    if (labels != labels_ || request.labels_revision != labels_revision_) {
        grid_.max_label = 0;
        if (labels) {
            grid_.label.assign(request.labels->labels, request.labels->labels + grid_.value.size());
            grid_.max_label = *std::max_element(grid_.label.begin(), grid_.label.end());
        } else {
            grid_.label.clear();
        }
        labels_ = labels;
        labels_revision_ = request.labels_revision;
    }
    return grid_;
}

} // namespace arbor::raycast
