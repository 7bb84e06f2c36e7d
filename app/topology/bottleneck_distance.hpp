// bottleneck_distance.hpp - the exact bottleneck distance between two
// persistence diagrams of finite points: the smallest t such that every point
// can be matched to a point of the other diagram or to the diagonal at
// L-infinity distance at most t (a point's distance to the diagonal is
// (death - birth) / 2).
//
// Exact, not approximate: the answer is one of the candidate values - a
// difference of two births, of two deaths, or a half persistence, since every
// edge of the augmented graph costs one of these - and the search runs over
// these values themselves, never over a tolerance.  It narrows the open
// interval (largest value known infeasible, smallest known feasible) by
// testing the median of a random sample of the candidates inside it (counted
// and drawn from sorted coordinates without listing the n*m differences) until
// at most a few million remain; those are listed, sorted and bisected.  Each
// test is a perfect-matching decision (bottleneck_matching.hpp).  Distances
// are compared as computed in double precision from the coordinates, the same
// expression everywhere, so the result is the exact bottleneck distance of
// the diagrams as stored: for integer values (and float32 values) every
// difference is exact.
#pragma once

#include "plane_point_tree.hpp"

#include <cstddef>
#include <span>

namespace arbor::topology {

struct BottleneckResult {
    double distance = 0.0;
    std::size_t matched_pairs = 0; // pairs point-to-point in an optimal matching (the rest: diagonal)
    int decisions = 0;             // perfect-matching tests run
};

// Points need death >= birth; points on the diagonal may be given and cost
// nothing.
BottleneckResult bottleneck_distance(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

} // namespace arbor::topology
