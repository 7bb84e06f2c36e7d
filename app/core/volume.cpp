#include "volume.hpp"

#include "huge_pages.hpp"
#include "volume_header.hpp"
#include "voxel_type.hpp"

#include <cstdlib>
#include <new>
#include <stdexcept>

namespace arbor {

std::array<double, 3> Geometry::position(double i, double j, double k) const
{
    const double g[3] = {spacing[0] * i, spacing[1] * j, spacing[2] * k};
    std::array<double, 3> p;
    for (int r = 0; r < 3; ++r)
        p[r] = origin[r] + direction[3 * r] * g[0] + direction[3 * r + 1] * g[1] +
               direction[3 * r + 2] * g[2];
    return p;
}

std::array<double, 3> Geometry::position_of(int64_t vertex) const
{
    const int64_t i = vertex % dims[0];
    const int64_t j = (vertex / dims[0]) % dims[1];
    const int64_t k = vertex / (dims[0] * dims[1]);
    return position(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
}

void Volume::Free::operator()(std::byte *p) const
{
    if (bytes >= kHugePageThreshold)
        free_large(p, bytes);
    else
        std::free(p);
}

Volume Volume::allocate(arbor_voxel_type type, const Geometry &geometry, ValueMapping mapping,
                        uint64_t max_bytes)
{
    arbor_volume header{};
    header.struct_size = sizeof(header);
    header.voxel_type = type;
    for (int a = 0; a < 3; ++a) {
        header.dims[a] = geometry.dims[a];
        header.spacing[a] = geometry.spacing[a];
        header.origin[a] = geometry.origin[a];
    }
    for (int e = 0; e < 9; ++e)
        header.direction[e] = geometry.direction[e];
    header.value_scale = mapping.scale;
    header.value_offset = mapping.offset;
    header.value_unit = mapping.unit.c_str();
    const std::string problem = check_volume_header(header, max_bytes);
    if (!problem.empty())
        throw std::invalid_argument(problem);

    Volume v;
    v.type_ = type;
    v.geometry_ = geometry;
    v.mapping_ = std::move(mapping);
    const uint64_t bytes = v.byte_size();
    // Large volumes in huge pages, faulted in at once: importers fill
    // hundreds of megabytes, and page faults are the largest fixed cost of
    // that on virtual machines.  Small ones 64-byte aligned on the heap.
    std::size_t rounded = static_cast<std::size_t>((bytes + 63) / 64 * 64);
    void *p = nullptr;
    if (rounded >= kHugePageThreshold) {
        rounded = mapped_bytes(rounded);
        p = allocate_large(rounded, Pages::Small);
    } else {
        p = std::aligned_alloc(64, rounded);
    }
    if (!p)
        throw std::bad_alloc();
    v.storage_ = std::unique_ptr<std::byte[], Free>(static_cast<std::byte *>(p), Free(rounded));
    return v;
}

Volume Volume::allocate(const arbor_volume &h, uint64_t max_bytes)
{
    Geometry g;
    for (int a = 0; a < 3; ++a) {
        g.dims[a] = h.dims[a];
        g.spacing[a] = h.spacing[a];
        g.origin[a] = h.origin[a];
    }
    for (int e = 0; e < 9; ++e)
        g.direction[e] = h.direction[e];
    ValueMapping m{h.value_scale, h.value_offset, h.value_unit ? h.value_unit : ""};
    return allocate(h.voxel_type, g, std::move(m), max_bytes);
}

uint64_t Volume::byte_size() const
{
    return static_cast<uint64_t>(voxel_count()) * arbor_voxel_size(type_);
}

double Volume::value(int64_t v) const
{
    return dispatch_voxel_type(type_, [&](auto t) {
        using T = decltype(t);
        return static_cast<double>(as<T>()[v]);
    });
}

arbor_volume Volume::view() const
{
    arbor_volume r{};
    r.struct_size = sizeof(r);
    r.voxel_type = type_;
    const int64_t s = arbor_voxel_size(type_);
    for (int a = 0; a < 3; ++a) {
        r.dims[a] = geometry_.dims[a];
        r.spacing[a] = geometry_.spacing[a];
        r.origin[a] = geometry_.origin[a];
    }
    r.strides[0] = s;
    r.strides[1] = s * geometry_.dims[0];
    r.strides[2] = s * geometry_.dims[0] * geometry_.dims[1];
    for (int e = 0; e < 9; ++e)
        r.direction[e] = geometry_.direction[e];
    r.value_scale = mapping_.scale;
    r.value_offset = mapping_.offset;
    r.value_unit = mapping_.unit.c_str();
    r.voxels = const_cast<std::byte *>(storage_.get());
    return r;
}

} // namespace arbor
