// wasserstein_distance.hpp - the exact p-Wasserstein distance between two
// persistence diagrams of finite points, L-infinity ground distance:
//   W_p(A, B) = ( min over matchings of the sum of d(a, b)^p )^(1/p)
// where every point goes to a point of the other diagram or to the diagonal
// (cost ((death - birth) / 2)^p).
//
// Method: the optimal matching is a min-cost flow (a transportation problem)
// on a sparse network, solved exactly by LEMON's network simplex:
//   - points on the diagonal are left out (they go to it at no cost);
//     identical points are merged into one node with their multiplicity;
//   - nodes: A's points (supply = multiplicity), B's points (demand), one
//     diagonal node on each side (A's diagonal supplies |B|, B's demands |A|);
//   - arcs: every point to the other side's diagonal, diagonal to diagonal
//     at cost 0, and point-to-point arcs a -> b.  Only the pairs with
//     d(a, b)^p < diag(a) + diag(b) can be in an optimal matching (otherwise
//     sending both to the diagonal is no dearer), and of those only the ones
//     that can lower the cost are ever added (column generation): the network
//     starts with each point's nearest points of the other diagram, and after
//     each solve a k-d tree walk (pruned by subtree bounds) finds every pair
//     whose reduced cost under the solver's node potentials is negative; they
//     are added and the problem is solved again.  When none is left the
//     potentials are a feasible dual of the complete problem, which proves the
//     flow optimal for it: the result is the exact optimum, not an
//     approximation that depends on how many arcs were kept.
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
