// matching_costs.hpp - the integer costs d^p of the Wasserstein matching, as
// the network simplex needs them (wasserstein_distance.hpp).
//
// Exact scale: every coordinate an integer (|x| <= 2^40) and p an integer,
// and the largest cost small enough that no sum of costs along the solver's
// spanning tree can overflow 63 bits: the cost of distance d is (2 d)^p, an
// integer (2 d is an integer since d is a difference of integers or half
// one), and a real cost is that divided by 2^p, exactly.
// Rounded scale otherwise: the cost is round(S * d^p), S a power of two as
// large as that overflow bound allows; each cost is then within 1/(2 S) of
// S * d^p / S.
// Costs beyond twice the largest diagonal cost saturate: no pair that dear can
// be in an optimal matching, and saturation keeps the map monotone.
#pragma once

#include "plane_point_tree.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace arbor::topology {

class MatchingCosts {
public:
    // The scale for matching `a` against `b` (points off the diagonal) in a
    // network of `nodes` nodes.
    MatchingCosts(std::span<const PlanePoint> a, std::span<const PlanePoint> b, double p, std::size_t nodes);

    bool exact() const { return exact_; }
    // Cost of a pair at L-infinity distance d (monotone in d).
    int64_t of_distance(double d) const;
    // Cost of sending a point to the diagonal.
    int64_t of_diagonal(PlanePoint q) const { return of_distance((q.y - q.x) * 0.5); }
    // d^p, unrounded (long double).
    long double real(double d) const;
    // Exact scale: a cost in real units.  Rounded scale: 1 / S, twice the
    // largest rounding error of one cost.
    long double to_real(int64_t cost) const;
    long double resolution() const { return 1.0L / scale_; }

private:
    double p_;
    int integer_p_ = 0; // p when it is an integer, else 0
    bool exact_ = false;
    long double scale_ = 1.0L; // S (rounded scale) or 2^p (exact scale: cost / scale_ = real)
    long double saturated_ = 0.0L;
};

} // namespace arbor::topology
