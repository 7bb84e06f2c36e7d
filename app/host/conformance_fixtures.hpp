// conformance_fixtures.hpp - small, valid inputs for every plugin kind that
// the conformance checks feed to plugins: a ramp volume of any voxel type, a
// three-branch tree with measures, transfer functions, a camera, an image.
#pragma once

#include "branch_tree_arrays.hpp"

#include <arbor/arbor.h>

#include <cstdint>
#include <vector>

namespace arbor {

// An n^3 volume of `type` whose values ramp with the voxel index.
class FixtureVolume {
public:
    FixtureVolume(arbor_voxel_type type, int64_t n);
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
    const arbor_branch_tree &record() const { return arrays_.record(); }
    arbor_measure_rows rows() const;   // every branch as a row
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
