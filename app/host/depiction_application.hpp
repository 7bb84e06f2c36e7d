// depiction_application.hpp - the host applying a depiction to transfer
// functions, for generators that leave it to the host (arbor_tf_set's
// depiction_by_host, ABI 1.4), with the formulas of depictor.h: per branch
// an opacity factor linear in value from its saddle to its extremum, its hue
// put in place of the colour's HSV hue, its vividness (CIELAB chroma at the
// colour's L* and hue angle) scaled by the saturation factor.
#pragma once

#include "colour_space.hpp"

#include <arbor/branch_tree.h>
#include <arbor/depictor.h>
#include <arbor/transfer_function.h>

namespace arbor {

// The depiction's opacity factor of branch b at stored value v.
double depiction_opacity(const arbor_depiction &d, const arbor_branch_tree &tree, uint32_t b, double value);

// A straight sRGB colour with branch b's hue (when not NaN) and vividness
// factor applied, clamped to [0, 1].
Rgb depiction_colour(const arbor_depiction &d, uint32_t b, const Rgb &colour);

// Applies the depiction to every lookup-table entry and control point of
// `set` (host-owned arrays, one branch per branch of `tree`; `points` holds
// point_offsets[branch_count] points).
void apply_depiction(const arbor_depiction &d, const arbor_branch_tree &tree, arbor_tf_set &set,
                     arbor_tf_point *points);

} // namespace arbor
