// conformance_fixtures.hpp - valid inputs for every plugin kind that the
// conformance checks feed to plugins: a ramp volume of any voxel type and
// size (1x1x1 up), a three-branch tree with measures, a tree of any size (a
// lone root; thousands of branches), transfer functions, a camera, an image.
#pragma once

#include "branch_tree_arrays.hpp"

#include <arbor/arbor.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace arbor {

// An n^3 (or nx*ny*nz) volume of `type` whose values ramp with the voxel
// index (every 100 voxels).
class FixtureVolume {
public:
    FixtureVolume(arbor_voxel_type type, int64_t n) : FixtureVolume(type, n, n, n) {}
    FixtureVolume(arbor_voxel_type type, int64_t nx, int64_t ny, int64_t nz);
    // The smallest and largest stored value.
    std::pair<double, double> value_range() const;
    // False when a floating-point voxel is NaN or infinite.
    bool all_finite() const;
    arbor_volume &record() { return record_; }

private:
    std::vector<unsigned char> bytes_;
    arbor_volume record_{};
};

// Root branch 0 (minimum 0 .. maximum 100) with a maximum child (branch 1,
// saddle 40 .. 90) and a minimum child (branch 2, saddle 60 .. 10).
// A 3-branch tree: a root with a maximum and a minimum child.
class FixtureTree {
public:
    FixtureTree();
    // `branches` branches (1: the root alone): each branch's children lie
    // inside its value interval, four to a parent, maxima and minima in
    // turn, measures shrinking with depth; every relative measure in [0, 1].
    explicit FixtureTree(uint32_t branches);
    const arbor_branch_tree &record() const { return arrays_.record(); }
    arbor_measure_rows rows() const;   // every branch as a row
    // Branches first .. first + count - 1 as rows (a batch without the root
    // when first > 0).
    arbor_measure_rows rows(uint32_t first, uint32_t count) const;
    uint32_t size() const { return record().branch_count; }
    arbor_measure_rows schema() const; // columns only

private:
    BranchTreeArrays arrays_;
};

// Output records with host-owned arrays, sized for `branches` (depictions:
// DepictionRecord, tf_generation.hpp).
class FixtureTfSet {
public:
    FixtureTfSet(uint32_t branches, uint32_t lut_size);
    arbor_tf_set &record() { return record_; }
    // Fill every branch with an opacity ramp over [lo, hi] (for renderers).
    void fill_ramp(double lo, double hi);

private:
    std::vector<double> domain_;
    std::vector<float> lut_;
    std::vector<uint32_t> offsets_;
    arbor_tf_set record_{};
};

class FixtureImage {
public:
    FixtureImage(uint32_t width, uint32_t height);
    arbor_image &record() { return record_; }
    // True when every value is finite and inside [0, 1].
    bool all_in_unit_range() const;
    const std::vector<float> &rgba() const { return rgba_; }

private:
    std::vector<float> rgba_, depth_;
    arbor_image record_{};
};

// An orthographic camera looking at the centre of an n^3 unit-spacing volume.
arbor_camera fixture_camera(int64_t n);

} // namespace arbor
