// volume.hpp - the host's scalar volume: a regular grid with LPS geometry, a
// stored->physical value mapping, and voxel memory it owns.
//
// Volume::view() gives the borrowed arbor_volume record that plugins receive.
// Memory is only ever allocated through Volume::allocate, after the header was
// checked against the limits in volume_header.hpp, so no input can make the
// host attempt a huge allocation.
#pragma once

#include <arbor/volume.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace arbor {

struct Geometry {
    std::array<int64_t, 3> dims{0, 0, 0};
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0};
    std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1}; // row-major

    int64_t voxel_count() const { return dims[0] * dims[1] * dims[2]; }
    // LPS position (mm) of the centre of voxel (i, j, k).
    std::array<double, 3> position(double i, double j, double k) const;
    // LPS position of a voxel index i + nx*(j + ny*k).
    std::array<double, 3> position_of(int64_t vertex) const;
};

struct ValueMapping {
    double scale = 1.0;
    double offset = 0.0;
    std::string unit;

    double physical(double stored) const { return stored * scale + offset; }
};

class Volume {
public:
    Volume() = default;

    // Allocates uninitialised voxel memory for a header that passed
    // check_volume_header (throws std::invalid_argument otherwise, and
    // std::bad_alloc when the system refuses).
    static Volume allocate(arbor_voxel_type type, const Geometry &geometry, ValueMapping mapping,
                           uint64_t max_bytes);
    // The same from an importer's header record.
    static Volume allocate(const arbor_volume &header, uint64_t max_bytes);

    bool empty() const { return !storage_; }
    arbor_voxel_type type() const { return type_; }
    const Geometry &geometry() const { return geometry_; }
    Geometry &geometry() { return geometry_; }
    const ValueMapping &mapping() const { return mapping_; }
    ValueMapping &mapping() { return mapping_; }
    int64_t voxel_count() const { return geometry_.voxel_count(); }
    uint64_t byte_size() const;

    void *data() { return storage_.get(); }
    const void *data() const { return storage_.get(); }
    template <class T> T *as() { return static_cast<T *>(data()); }
    template <class T> const T *as() const { return static_cast<const T *>(data()); }

    // Stored value of voxel index v as a double.
    double value(int64_t v) const;

    // Borrowed record for plugins; valid while this Volume lives unchanged.
    arbor_volume view() const;

private:
    // Knows how the block was allocated (core/huge_pages.hpp) by its size.
    struct Free {
        Free() noexcept : bytes(0) {}
        explicit Free(std::size_t size) noexcept : bytes(size) {}
        void operator()(std::byte *p) const;
        std::size_t bytes;
    };
    arbor_voxel_type type_ = ARBOR_VOXEL_UNKNOWN;
    Geometry geometry_;
    ValueMapping mapping_;
    std::unique_ptr<std::byte[], Free> storage_;
};

} // namespace arbor
