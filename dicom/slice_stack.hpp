// slice_stack.hpp - how a series' frames become the slices of one regular
// grid: order along the slice normal, spacing from the positions, and what to
// do about irregular gaps, missing slices and gantry tilt.
//
// Pure geometry, no DICOM parsing: the input is each frame's Image Position
// (Patient) and the series' Image Orientation (Patient).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace arbor::dicom {

using Vec3 = std::array<double, 3>;

struct StackPolicy {
    bool resample_irregular = true; // else refuse gaps that differ
    bool fill_missing = false;      // else refuse gaps that skip slices
    bool correct_tilt = true;       // else refuse gantry tilt
};

// Output slice = (1 - t) * frame a + t * frame b (frame indices into the
// input order; a == b and t == 0 for a slice taken as it is).
struct SliceSource {
    std::size_t a = 0;
    std::size_t b = 0;
    double t = 0.0;
};

struct SliceStack {
    Vec3 origin{};   // position of output slice 0, pixel (0, 0)
    Vec3 normal{};   // unit slice normal, row x column direction
    double spacing = 0.0; // between output slices, mm
    std::vector<SliceSource> slices;
    // In-plane offset (along the row direction, along the column direction,
    // mm) of each input frame from the line through origin along the normal;
    // empty when every frame sits on it (no tilt).
    std::vector<std::array<double, 2>> frame_offsets;
    std::vector<std::string> notes; // corrections made, in words
};

// The unit normal of an orientation (row cosines, column cosines); throws
// when they are not two orthogonal unit vectors.
Vec3 slice_normal(const std::array<double, 6> &orientation);

// Plans the stack of `positions` (one per frame).  `single_spacing` (> 0) is
// the slice spacing when there is a single frame.  Throws std::runtime_error naming
// the problem when the policy refuses it or no stack is possible
// (several frames at one position).
SliceStack plan_slice_stack(const std::vector<Vec3> &positions,
                            const std::array<double, 6> &orientation,
                            const std::array<double, 2> &pixel_spacing, double single_spacing,
                            const StackPolicy &policy);

} // namespace arbor::dicom
