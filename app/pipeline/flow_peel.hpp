// flow_peel.hpp - the flow rate Q as the balanced picture's own axis.
//
// The visibility balance (visibility_balance.hpp) chooses the default
// picture: it is taken once, on the transfer functions at the generator's
// default flow rate Q0, and kept while only Q moves, so it cannot undo the
// slider.  Moving Q then peels the layers as the residue flow says (the
// generator's functions at Q), and, because an outer layer is thick enough
// to stay opaque whatever band of opacity the flow leaves it (on brain1 the
// root's share moved 67 % -> 61 % over Q 10 .. 1000 without balance), the
// optical depth of each branch is also multiplied by
//
//     peel_b(Q) = (Q0 / Q) ^ (h_b / h_root),
//
// h_b the height of b's subtree (the longest path down to a leaf).  The
// root, the outermost layer, thins in proportion to Q; a leaf, which the
// residue flow lets pass nothing on (its head loss is 0), keeps its depth;
// the layers between thin in between.  So over Q every branch's optical
// depth is monotonic - outer layers fall, and the inner ones, with less in
// front of them, come forward - and at Q0 the picture is the balanced one.
#pragma once

#include <arbor/branch_tree.h>

#include <vector>

namespace arbor::pipeline {

// Per branch of `tree` its optical depth's multiplier at flow-rate ratio
// q_ratio = Q / Q0 (> 0); all 1 at q_ratio 1 or for a single branch.
std::vector<double> flow_peel(const arbor_branch_tree &tree, double q_ratio);

// scale[b] * peel[b] (peel empty: scale).
std::vector<double> peeled_scale(const std::vector<double> &scale, const std::vector<double> &peel);

} // namespace arbor::pipeline
