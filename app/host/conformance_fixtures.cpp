#include "conformance_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace arbor {

FixtureVolume::FixtureVolume(arbor_voxel_type type, int64_t nx, int64_t ny, int64_t nz)
{
    const uint32_t size = arbor_voxel_size(type);
    const int64_t count = nx * ny * nz;
    bytes_.assign(static_cast<std::size_t>(count * size), 0);
    for (int64_t v = 0; v < count; ++v) {
        const double x = static_cast<double>(v % 100);
        unsigned char *p = bytes_.data() + v * size;
        switch (type) {
        case ARBOR_VOXEL_U8: { uint8_t t = static_cast<uint8_t>(x); std::memcpy(p, &t, 1); break; }
        case ARBOR_VOXEL_I8: { int8_t t = static_cast<int8_t>(x - 50); std::memcpy(p, &t, 1); break; }
        case ARBOR_VOXEL_U16: { uint16_t t = static_cast<uint16_t>(x * 10); std::memcpy(p, &t, 2); break; }
        case ARBOR_VOXEL_I16: { int16_t t = static_cast<int16_t>(x * 10 - 500); std::memcpy(p, &t, 2); break; }
        case ARBOR_VOXEL_U32: { uint32_t t = static_cast<uint32_t>(x * 1000); std::memcpy(p, &t, 4); break; }
        case ARBOR_VOXEL_I32: { int32_t t = static_cast<int32_t>(x * 1000 - 50000); std::memcpy(p, &t, 4); break; }
        case ARBOR_VOXEL_F32: { float t = static_cast<float>(x / 100); std::memcpy(p, &t, 4); break; }
        case ARBOR_VOXEL_F64: { double t = x / 100; std::memcpy(p, &t, 8); break; }
        default: break;
        }
    }
    record_.struct_size = sizeof(record_);
    record_.voxel_type = type;
    const int64_t dims[3] = {nx, ny, nz};
    for (int a = 0; a < 3; ++a) {
        record_.dims[a] = dims[a];
        record_.spacing[a] = 1.0;
    }
    record_.strides[0] = size;
    record_.strides[1] = size * nx;
    record_.strides[2] = size * nx * ny;
    record_.direction[0] = record_.direction[4] = record_.direction[8] = 1.0;
    record_.value_scale = 1.0;
    record_.value_unit = "";
    record_.voxels = bytes_.data();
}

std::pair<double, double> FixtureVolume::value_range() const
{
    const int64_t count = record_.dims[0] * record_.dims[1] * record_.dims[2];
    const uint32_t size = arbor_voxel_size(record_.voxel_type);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int64_t v = 0; v < count; ++v) {
        const unsigned char *p = bytes_.data() + v * size;
        double x = 0;
        switch (record_.voxel_type) {
        case ARBOR_VOXEL_U8: { uint8_t t; std::memcpy(&t, p, 1); x = t; break; }
        case ARBOR_VOXEL_I8: { int8_t t; std::memcpy(&t, p, 1); x = t; break; }
        case ARBOR_VOXEL_U16: { uint16_t t; std::memcpy(&t, p, 2); x = t; break; }
        case ARBOR_VOXEL_I16: { int16_t t; std::memcpy(&t, p, 2); x = t; break; }
        case ARBOR_VOXEL_U32: { uint32_t t; std::memcpy(&t, p, 4); x = t; break; }
        case ARBOR_VOXEL_I32: { int32_t t; std::memcpy(&t, p, 4); x = t; break; }
        case ARBOR_VOXEL_F32: { float t; std::memcpy(&t, p, 4); x = t; break; }
        case ARBOR_VOXEL_F64: { double t; std::memcpy(&t, p, 8); x = t; break; }
        default: break;
        }
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    return {lo, hi};
}

bool FixtureVolume::all_finite() const
{
    const std::size_t count = bytes_.size() / std::max<uint32_t>(1, arbor_voxel_size(record_.voxel_type));
    for (std::size_t v = 0; v < count; ++v) {
        double x = 0;
        if (record_.voxel_type == ARBOR_VOXEL_F32) {
            float t;
            std::memcpy(&t, bytes_.data() + 4 * v, 4);
            x = t;
        } else if (record_.voxel_type == ARBOR_VOXEL_F64) {
            std::memcpy(&x, bytes_.data() + 8 * v, 8);
        }
        if (!std::isfinite(x))
            return false;
    }
    return true;
}

FixtureTree::FixtureTree()
{
    BranchTreeArrays &a = arrays_;
    a.resize(3);
    a.parent = {-1, 0, 0};
    a.kind = {ARBOR_EXTREMUM_MAXIMUM, ARBOR_EXTREMUM_MAXIMUM, ARBOR_EXTREMUM_MINIMUM};
    a.saddle_vertex = {0, 10, 20};
    a.extremum_vertex = {511, 300, 100};
    a.saddle_value = {0, 40, 60};
    a.extremum_value = {100, 90, 10};
    a.saddle_position = {0, 0, 0, 2, 1, 0, 4, 2, 0};
    a.extremum_position = {7, 7, 7, 4, 5, 4, 4, 4, 1};
    // persistence, volume, volume-mm3, hypervolume, relative hypervolume
    a.measures = {100, 512, 512, 25600, 25600,
                  50,  40,  40,  3200,  1000,
                  50,  30,  30,  600,   800};
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 5; ++c)
            a.relative[r * 5 + c] = a.measures[r * 5 + c] / a.measures[c];
    a.link();
}

FixtureTree::FixtureTree(uint32_t branches)
{
    BranchTreeArrays &a = arrays_;
    const std::size_t n = branches == 0 ? 1 : branches, width = BranchTreeArrays::kMeasureCount;
    a.resize(n);
    std::vector<uint32_t> depth(n, 0);
    for (std::size_t b = 0; b < n; ++b) {
        a.saddle_vertex[b] = static_cast<int64_t>(2 * b);
        a.extremum_vertex[b] = static_cast<int64_t>(2 * b + 1);
        for (int c = 0; c < 3; ++c) {
            a.saddle_position[3 * b + c] = static_cast<double>((b + static_cast<std::size_t>(c)) % 8);
            a.extremum_position[3 * b + c] = static_cast<double>((2 * b + static_cast<std::size_t>(c)) % 8);
        }
        double volume = 512, persistence = 1000;
        if (b == 0) {
            a.parent[b] = -1;
            a.kind[b] = ARBOR_EXTREMUM_MAXIMUM;
            a.saddle_value[b] = 0;
            a.extremum_value[b] = 1000;
        } else {
            const std::size_t p = (b - 1) / 4;
            a.parent[b] = static_cast<int32_t>(p);
            depth[b] = depth[p] + 1;
            const double lo = std::min(a.saddle_value[p], a.extremum_value[p]),
                         hi = std::max(a.saddle_value[p], a.extremum_value[p]);
            const double at = 0.2 + 0.15 * static_cast<double>((b - 1) % 4); // 0.2 .. 0.65 of the way up
            a.saddle_value[b] = lo + at * (hi - lo);
            const bool maximum = b % 2 == 1;
            a.kind[b] = maximum ? ARBOR_EXTREMUM_MAXIMUM : ARBOR_EXTREMUM_MINIMUM;
            a.extremum_value[b] = maximum ? a.saddle_value[b] + 0.5 * (hi - a.saddle_value[b])
                                          : a.saddle_value[b] - 0.5 * (a.saddle_value[b] - lo);
            persistence = std::fabs(a.extremum_value[b] - a.saddle_value[b]);
            volume = std::max(1.0, std::floor(a.measures[p * width + 1] / 5));
        }
        // persistence, volume, volume-mm3, hypervolume, relative hypervolume
        const double row[] = {persistence, volume, volume, volume * persistence / 2, volume * persistence / 3};
        for (std::size_t c = 0; c < width; ++c) {
            a.measures[b * width + c] = row[c];
            a.relative[b * width + c] = row[c] / a.measures[c];
        }
    }
    a.link();
}

arbor_measure_rows FixtureTree::rows() const
{
    return rows(0, size());
}

arbor_measure_rows FixtureTree::rows(uint32_t first, uint32_t count) const
{
    const std::size_t at = std::size_t{first} * BranchTreeArrays::kMeasureCount;
    arbor_measure_rows r{};
    r.struct_size = sizeof(r);
    r.row_count = count;
    r.measure_count = BranchTreeArrays::kMeasureCount;
    r.measure_ids = BranchTreeArrays::kMeasureIds;
    r.measures = record().measures + at;
    r.relative_measures = record().relative_measures + at;
    r.extremum_kind = record().extremum_kind + first;
    r.saddle_value = record().saddle_value + first;
    r.extremum_value = record().extremum_value + first;
    r.root_row = first == 0 ? 0 : -1;
    r.value_scale = 1.0;
    r.value_unit = "";
    return r;
}

arbor_measure_rows FixtureTree::schema() const
{
    arbor_measure_rows r = rows();
    r.row_count = 0;
    r.extremum_kind = nullptr;
    r.saddle_value = r.extremum_value = nullptr;
    r.root_row = -1;
    return r;
}

FixtureTfSet::FixtureTfSet(uint32_t n, uint32_t lut_size)
    : domain_(2 * n, 0.0), lut_(static_cast<std::size_t>(n) * lut_size * 4, 0.0f), offsets_(n + 1, 0)
{
    record_.struct_size = sizeof(record_);
    record_.branch_count = n;
    record_.lut_size = lut_size;
    record_.opacity_unit_distance = 1.0;
    record_.domain = domain_.data();
    record_.lut = lut_.data();
    record_.point_offsets = offsets_.data();
    record_.points = nullptr;
}

void FixtureTfSet::fill_ramp(double lo, double hi)
{
    const uint32_t n = record_.branch_count, size = record_.lut_size;
    for (uint32_t b = 0; b < n; ++b) {
        domain_[2 * b] = lo;
        domain_[2 * b + 1] = hi;
        for (uint32_t i = 0; i < size; ++i) {
            float *e = &lut_[(static_cast<std::size_t>(b) * size + i) * 4];
            const float t = static_cast<float>(i) / static_cast<float>(size - 1);
            e[0] = t;
            e[1] = 1.0f - t;
            e[2] = 0.5f;
            e[3] = 0.2f * t;
        }
    }
}

FixtureImage::FixtureImage(uint32_t w, uint32_t h)
    : rgba_(static_cast<std::size_t>(w) * h * 4, -1.0f), depth_(static_cast<std::size_t>(w) * h, 0.0f)
{
    record_.struct_size = sizeof(record_);
    record_.width = w;
    record_.height = h;
    record_.row_stride = 4 * static_cast<int64_t>(w);
    record_.rgba = rgba_.data();
    record_.depth = depth_.data();
}

bool FixtureImage::all_in_unit_range() const
{
    for (float v : rgba_)
        if (!std::isfinite(v) || v < 0.0f || v > 1.0f)
            return false;
    return true;
}

arbor_camera fixture_camera(int64_t n)
{
    arbor_camera c{};
    c.struct_size = sizeof(c);
    c.projection = ARBOR_PROJECTION_ORTHOGRAPHIC;
    const double mid = 0.5 * static_cast<double>(n - 1);
    c.focal_point[0] = c.focal_point[1] = c.focal_point[2] = mid;
    c.position[0] = mid;
    c.position[1] = mid - 4.0 * static_cast<double>(n);
    c.position[2] = mid;
    c.view_up[2] = 1.0;
    c.view_angle = 30.0;
    c.parallel_scale = static_cast<double>(n);
    return c;
}

} // namespace arbor
