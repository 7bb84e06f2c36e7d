// wasserstein_distance.hpp - the exact p-Wasserstein distance between two
// persistence diagrams of finite points, L-infinity ground distance:
//   W_p(A, B) = ( min over matchings of the sum of d(a, b)^p )^(1/p)
// where every point goes to a point of the other diagram or to the diagonal
// (cost ((death - birth) / 2)^p).
//
// Method: everything starts on the diagonal, at the sum of all diagonal
// costs, and matching a to b changes it by the pair's gain
//   g(a, b) = d(a, b)^p - diag(a) - diag(b);
// the optimum is that sum plus a minimum-gain matching, a maximum-weight
// bipartite b-matching solved exactly as a min-cost flow by LEMON's network
// simplex (source -> a with a's multiplicity, a -> b at the gain, b -> sink,
// source -> sink for what stays on the diagonal):
//   - points on the diagonal are left out (they go to it at no cost);
//     identical points are merged into one node with their multiplicity;
//   - only pairs with a negative gain can be in an optimal matching (a pair
//     with g >= 0 is no dearer sent to the diagonal), and they are all that
//     is ever considered: a k-d tree walk lists them (pruned by subtree
//     bounds), they split into connected components that are independent
//     problems, and each is solved once - nothing is left out;
//   - when there are too many to list (more than 8M: real-valued noise), they
//     are generated: the network starts with each point's nearest points of
//     the other diagram, and after each solve a walk finds every pair whose
//     reduced cost under the solver's node potentials is negative; they are
//     added and the problem solved again.  When none is left the potentials
//     are a feasible dual of the complete problem, which proves the flow
//     optimal for it.
// Either way the result is the exact optimum, not an approximation that
// depends on how many pairs are kept.
//
// Costs must be integers for the network simplex.  When every coordinate is
// an integer and p is an integer (any integer-valued volume) the costs are
// (2 d)^p exactly and the distance is exact, the p-th root being the only
// rounding.  Otherwise each cost d^p is rounded to a multiple of 2^-k (k as
// large as 63-bit sums allow, relative to the largest cost), the matching is
// optimal for those costs, its cost is then summed from the unrounded d^p,
// and `error_bound` says by how much the exact optimum can be smaller.
#pragma once

#include "plane_point_tree.hpp"

#include <cstddef>
#include <span>

namespace arbor::topology {

struct WassersteinResult {
    double distance = 0.0;           // W_p
    long double cost = 0.0;          // W_p^p, the optimal matching's sum of d^p
    std::size_t matched_pairs = 0;   // point-to-point pairs in it (the rest: diagonal)
    bool exact = true;               // integer costs: exact up to the final root
    double error_bound = 0.0;        // !exact: the exact W_p is in [distance - error_bound, distance]
    int solves = 0;                  // network simplex runs (column generation rounds)
    std::size_t arcs = 0;            // point-to-point arcs of the last network
};

// Points need death >= birth; p >= 1 (std::invalid_argument otherwise).
WassersteinResult wasserstein_distance(std::span<const PlanePoint> a, std::span<const PlanePoint> b, double p);

} // namespace arbor::topology
