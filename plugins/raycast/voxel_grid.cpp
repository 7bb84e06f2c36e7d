#include "voxel_grid.hpp"
#include "cancellation.hpp"

#include <arbor/sdk/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

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
void copy_values(const arbor_volume &v, UnsetVector<float> &out, const sdk::Task &task)
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

// Central differences in index space (one-sided at the faces), taken to LPS
// by the inverse transpose of the grid's matrix.
class WorldGradient {
public:
    explicit WorldGradient(const VoxelGrid &g) : g_(g)
    {
        for (int c = 0; c < 9; ++c)
            inv_[c] = static_cast<float>(g.to_voxel[c]); // rows of M^-1 = columns of M^-T
    }

    std::array<float, 3> at(int64_t i, int64_t j, int64_t k) const
    {
        const float *v = g_.value.data();
        const int64_t sx = 1, sy = g_.nx, sz = g_.nx * g_.ny;
        const int64_t at = i + sy * j + sz * k;
        const auto diff = [&](int64_t x, int64_t n, int64_t stride) {
            const int64_t lo = x > 0 ? stride : 0, hi = x + 1 < n ? stride : 0;
            return lo + hi == 0 ? 0.0f : (v[at + hi] - v[at - lo]) / static_cast<float>((lo + hi) / stride);
        };
        const float gx = diff(i, g_.nx, sx), gy = diff(j, g_.ny, sy), gz = diff(k, g_.nz, sz);
        return {inv_[0] * gx + inv_[3] * gy + inv_[6] * gz, inv_[1] * gx + inv_[4] * gy + inv_[7] * gz,
                inv_[2] * gx + inv_[5] * gy + inv_[8] * gz};
    }

private:
    const VoxelGrid &g_;
    float inv_[9];
};

inline float length(const std::array<float, 3> &w) { return std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]); }

// The index-space gradients of row (j, k), as WorldGradient::at takes them,
// a row at a time so that the loops vectorise: central differences inside,
// one-sided at the faces, 0 along an axis of one voxel.
void row_gradients(const VoxelGrid &g, int64_t j, int64_t k, float *gx, float *gy, float *gz)
{
    const int64_t nx = g.nx, sy = g.nx, sz = g.nx * g.ny;
    const float *v = g.value.data() + g.index(0, j, k);
    const float *ylo = j > 0 ? v - sy : v, *yhi = j + 1 < g.ny ? v + sy : v;
    const float *zlo = k > 0 ? v - sz : v, *zhi = k + 1 < g.nz ? v + sz : v;
    const float yd = j > 0 && j + 1 < g.ny ? 0.5f : 1.0f, zd = k > 0 && k + 1 < g.nz ? 0.5f : 1.0f;
    for (int64_t i = 0; i < nx; ++i) {
        gy[i] = (yhi[i] - ylo[i]) * yd;
        gz[i] = (zhi[i] - zlo[i]) * zd;
    }
    for (int64_t i = 1; i + 1 < nx; ++i)
        gx[i] = (v[i + 1] - v[i - 1]) * 0.5f;
    gx[0] = nx > 1 ? v[1] - v[0] : 0.0f;
    if (nx > 1)
        gx[nx - 1] = v[nx - 1] - v[nx - 2];
}

// Rounded half away from zero, like lround, for |x| <= 127.5.
inline int8_t quantize(float x) { return static_cast<int8_t>(x < 0 ? x - 0.5f : x + 0.5f); }

// Unit gradient directions per voxel for shading; gradients far below the
// field's typical change per voxel count as flat (no shading there).  Their
// magnitudes are kept in 8 bits relative to the 99.5th percentile, taken
// from about a million voxels first: what boundary-emphasis opacity needs.
// One pass, and no per-voxel array beyond the result.
void compute_normals(VoxelGrid &g, const sdk::Task &task)
{
    using Range = std::pair<float, float>;
    const Range range = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, g.value.size(), std::size_t{1} << 20),
        Range{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()},
        [&](const tbb::blocked_range<std::size_t> &r, Range m) {
            for (std::size_t v = r.begin(); v != r.end(); ++v) {
                m.first = std::min(m.first, g.value[v]);
                m.second = std::max(m.second, g.value[v]);
            }
            return m;
        },
        [](Range a, Range b) { return Range{std::min(a.first, b.first), std::max(a.second, b.second)}; });
    const float flat =
        g.value.empty() ? 0.0f : static_cast<float>(1e-3 * (range.second - range.first) / g.min_spacing);
    const WorldGradient gradient(g);
    const std::size_t voxels = g.value.size();
    std::vector<float> sample;
    const std::size_t stride = std::max<std::size_t>(1, voxels / (1 << 20));
    sample.reserve(voxels / stride + 1);
    for (std::size_t v = 0; v < voxels; v += stride) {
        const int64_t i = static_cast<int64_t>(v) % g.nx, j = (static_cast<int64_t>(v) / g.nx) % g.ny,
                      k = static_cast<int64_t>(v) / (g.nx * g.ny);
        sample.push_back(length(gradient.at(i, j, k)));
    }
    const auto at = sample.begin() + static_cast<std::ptrdiff_t>(0.995 * (sample.size() - 1));
    std::nth_element(sample.begin(), at, sample.end());
    const float scale = 255.0f / (*at > 0 ? *at : 1.0f);
    g.gradient_scale = scale;
    g.flat_gradient = flat;

    g.surface.resize(voxels);
    float m[9];
    for (int c = 0; c < 9; ++c)
        m[c] = static_cast<float>(g.to_voxel[c]);
    for_slabs(g.nz, task, [&](int64_t k) {
        std::vector<float> row(6 * static_cast<std::size_t>(g.nx));
        float *gx = row.data(), *gy = gx + g.nx, *gz = gy + g.nx, *wx = gz + g.nx, *wy = wx + g.nx, *wz = wy + g.nx;
        for (int64_t j = 0; j < g.ny; ++j) {
            row_gradients(g, j, k, gx, gy, gz);
            // To LPS, as WorldGradient::at does, term for term.
            for (int64_t i = 0; i < g.nx; ++i) {
                wx[i] = m[0] * gx[i] + m[3] * gy[i] + m[6] * gz[i];
                wy[i] = m[1] * gx[i] + m[4] * gy[i] + m[7] * gz[i];
                wz[i] = m[2] * gx[i] + m[5] * gy[i] + m[8] * gz[i];
            }
            const std::size_t v0 = g.index(0, j, k);
            Surface *surface = g.surface.data() + v0;
            for (int64_t i = 0; i < g.nx; ++i) {
                const float len = std::sqrt(wx[i] * wx[i] + wy[i] * wy[i] + wz[i] * wz[i]);
                // Flat: no direction to shade by.
                const float unit = len <= flat ? 0.0f : 127.0f / len;
                surface[i] = {{quantize(wx[i] * unit), quantize(wy[i] * unit), quantize(wz[i] * unit)},
                              static_cast<uint8_t>(std::min(255.0f, len * scale + 0.5f))};
            }
        }
    });
}

} // namespace

int LabelGrid::width_for(uint32_t max_label)
{
    return max_label < 128 ? 1 : max_label < 32768 ? 2 : 4;
}

void LabelGrid::assign(const uint32_t *labels, const std::array<int64_t, 3> &dims, uint32_t max_label)
{
    if (max_label >= (1u << 31))
        sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "label " + std::to_string(max_label) + " is too large");
    clear();
    width_ = width_for(max_label);
    const int64_t nx = dims[0], ny = dims[1], nz = dims[2];
    size_ = static_cast<std::size_t>(nx * ny * nz);
    // Sized unwritten, then every word set once.
    if (width_ == 1)
        narrow_.resize(size_);
    else if (width_ == 2)
        medium_.resize(size_);
    else
        wide_.resize(size_);
    // The cell at (i, j, k) spans (i..i+1, j..j+1, k..k+1), clamped into
    // the grid (an axis of one voxel has flat cells).
    tbb::parallel_for(tbb::blocked_range<int64_t>(0, ny * nz), [&](const tbb::blocked_range<int64_t> &rows) {
        for (int64_t row = rows.begin(); row != rows.end(); ++row) {
            const int64_t j = row % ny, k = row / ny;
            const int64_t dj = j + 1 < ny ? nx : 0, dk = k + 1 < nz ? nx * ny : 0;
            const std::size_t v0 = static_cast<std::size_t>(nx * row);
            const uint32_t *a = labels + v0, *b = a + dj, *c = a + dk, *d = a + dj + dk;
            for (int64_t i = 0; i < nx; ++i) {
                const int64_t di = i + 1 < nx ? 1 : 0;
                const uint32_t l = a[i];
                const bool mixed = (a[i + di] ^ l) | (b[i] ^ l) | (b[i + di] ^ l) | (c[i] ^ l) | (c[i + di] ^ l) |
                                   (d[i] ^ l) | (d[i + di] ^ l);
                set(v0 + static_cast<std::size_t>(i), l << 1 | (mixed ? 1u : 0u));
            }
        }
    });
}

void LabelGrid::clear()
{
    width_ = 0;
    size_ = 0;
    narrow_ = {};
    medium_ = {};
    wide_ = {};
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
        if (v.voxel_type == ARBOR_VOXEL_F32 || v.voxel_type == ARBOR_VOXEL_F64) // integers are finite
            for (float x : g.value)
                if (!std::isfinite(x))
                    sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the volume holds NaN or infinite values");
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                g.to_world[3 * r + c] = v.direction[3 * r + c] * v.spacing[c];
        g.to_voxel = inverse(g.to_world);
        g.origin = {v.origin[0], v.origin[1], v.origin[2]};
        g.min_spacing = std::min({v.spacing[0], v.spacing[1], v.spacing[2]});
        g.thick_slices = std::max({v.spacing[0], v.spacing[1], v.spacing[2]}) >= 2.0 * g.min_spacing;
        for (int a = 0; a < 3; ++a)
            g.resample_scale[a] =
                v.spacing[a] >= 2.0 * g.min_spacing ? static_cast<float>(v.spacing[a] / g.min_spacing) : 1.0f;
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
            const uint32_t *first = label_map->labels, *last = first + grid_.value.size();
            grid_.max_label = first == last ? 0 : *std::max_element(first, last);
            grid_.label.assign(first, dims, grid_.max_label);
            grid_.tree.assign(label_map);
            if (grid_.tree.size() <= grid_.max_label)
                grid_.tree.clear(); // labels the tree does not know: nearest-voxel labels
        } else {
            grid_.label.clear();
            grid_.tree.clear();
        }
        labels_ = labels;
        labels_revision_ = labels_revision;
    }
    return grid_;
}

} // namespace arbor::raycast
