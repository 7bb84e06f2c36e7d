// control_points.hpp - the control points of a transfer function as the
// editable form of its lookup table (transfer_function.h): a fingerprint
// that tells points changed in a file from points as they were written, and
// the table baked from points - linear in value between them, constant
// beyond the first and the last - for branches whose points were edited.
#pragma once

#include <arbor/transfer_function.h>

#include <cstdint>
#include <string>
#include <utility>

namespace arbor::pipeline {

// The colour components as transfer-function files write them: rounded to
// six decimals.
float file_component(float x);

// A fingerprint (16 hex digits) of `count` points, taken over their values
// and file components bit for bit.
std::string points_digest(const arbor_tf_point *points, std::size_t count);

// `lut_size` RGBA entries spanning `domain` evenly, from points in
// non-decreasing value (count >= 1).
void bake_from_points(const arbor_tf_point *points, std::size_t count, std::pair<double, double> domain,
                      uint32_t lut_size, float *rgba);

} // namespace arbor::pipeline
