// bottleneck_matching.hpp - the decision problem of the bottleneck distance:
// can every point of diagram A and of diagram B be matched, within L-infinity
// distance t, to a point of the other diagram or to the diagonal?
//
// The graph is the usual augmented one (Edelsbrunner and Harer; Kerber,
// Morozov and Nigmetov, "Geometry helps to compare persistence diagrams"):
//   left  = the points a_i of A, then the diagonal copies b'_j of B's points
//   right = the points b_j of B, then the diagonal copies a'_i of A's points
//   a_i - b_j    when linf(a_i, b_j) <= t
//   a_i - a'_i   when a_i's distance to the diagonal, (death - birth) / 2, is <= t
//   b'_j - b_j   likewise
//   b'_j - a'_i  always (two diagonal points, distance 0)
// and the answer is whether it has a perfect matching.  Hopcroft-Karp finds a
// maximum matching; its neighbour queries go to k-d trees (one for the
// breadth-first layering, one per layer for the augmenting searches) from
// which each point is removed once reached, so a phase costs O(n log n)
// rather than the O(n^2) edges (Efrat, Itai and Katz).
#pragma once

#include "plane_point_tree.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace arbor::topology {

class BottleneckMatching {
public:
    // The points must have death >= birth.
    BottleneckMatching(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

    // A maximum matching at threshold t; true when it is perfect.
    bool perfect_at(double t);

    // Of the last matching: pairs a_i - b_j (the rest went to the diagonal).
    std::size_t off_diagonal_pairs() const;

    // (death - birth) / 2, the distance to the diagonal, as every threshold
    // test computes it.
    static double half_persistence(PlanePoint p) { return (p.y - p.x) * 0.5; }

private:
    static constexpr int kNone = -1;

    // Right vertices reached in one layer, and what the augmenting search
    // takes from them.
    struct Layer {
        PlanePointTree b_points;        // points of B (positions: ids into b_)
        std::vector<int> a_copies;      // a'_i as right ids
        std::size_t next_copy = 0;      // a'_i before it are taken
    };

    int right_of_copy(std::size_t i) const { return static_cast<int>(b_.size() + i); }
    bool left_is_point(int u) const { return u < static_cast<int>(a_.size()); }
    bool right_is_point(int v) const { return v < static_cast<int>(b_.size()); }
    bool light_a(std::size_t i) const { return half_persistence(a_[i]) <= t_; }
    bool light_b(std::size_t j) const { return half_persistence(b_[j]) <= t_; }

    void greedy();
    bool layer_graph();   // breadth-first: false when no augmenting path exists
    void augment_along_layers();
    int take_in_layer(int u, std::size_t layer);

    std::vector<PlanePoint> a_, b_;
    PlanePointTree a_tree_;       // for the quick test of B's far points
    PlanePointTree b_tree_;       // for the greedy start and the layering
    double t_ = 0.0;
    std::vector<int> mate_left_, mate_right_;
    std::vector<int> right_layer_; // layer of each right vertex in this phase, -1 unreached
    std::vector<uint8_t> taken_;   // right vertex used by this phase's augmenting search
    std::vector<Layer> layers_;
    std::vector<int> layer_left_;  // left vertices by layer, flattened per phase
};

} // namespace arbor::topology
