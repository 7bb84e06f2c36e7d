// plane_point_tree.hpp - a static 2D k-d tree over points of the plane, for
// the L-infinity neighbour queries of the diagram distances: "any point not
// yet removed within distance r" (with removal, as the geometric
// Hopcroft-Karp matching of Efrat, Itai and Katz needs), the k nearest
// points, and a branch-and-bound walk with per-subtree aggregates.
//
// Layout: the points are permuted so that the subtree of the index range
// [lo, hi) has its splitting point at mid = (lo + hi) / 2, the left subtree
// at [lo, mid) and the right one at [mid + 1, hi).  Every position is the
// split of exactly one subtree, so per-subtree data (bounding box, alive
// count, aggregates) is stored by position.
//
// Distances follow linf_distance exactly: the pruning tests use the same
// floating-point differences, and rounding is monotone, so a pruned subtree
// never holds a point the direct test would accept.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace arbor::topology {

struct PlanePoint {
    double x = 0.0, y = 0.0; // birth, death
};

inline double linf_distance(PlanePoint a, PlanePoint b)
{
    const double dx = a.x > b.x ? a.x - b.x : b.x - a.x;
    const double dy = a.y > b.y ? a.y - b.y : b.y - a.y;
    return dx > dy ? dx : dy;
}

class PlanePointTree {
public:
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);

    struct Box {
        double x0, x1, y0, y1;
        // Lower bound on linf_distance(q, p) for every p in the box.
        double distance_from(PlanePoint q) const;
    };

    PlanePointTree() = default;
    // The tree over all points; id(position) is the point's index.
    explicit PlanePointTree(std::span<const PlanePoint> points);
    // The tree over points[ids[i]] (none when ids is empty).
    PlanePointTree(std::span<const PlanePoint> points, std::span<const uint32_t> ids);

    std::size_t size() const { return points_.size(); }
    PlanePoint point(std::size_t position) const { return points_[position]; }
    uint32_t id(std::size_t position) const { return ids_[position]; }

    // Every point alive again.
    void revive_all();
    bool alive(std::size_t position) const { return alive_[position] != 0; }
    void remove(std::size_t position);
    // A position of an alive point p with linf_distance(q, p) <= r, or npos.
    std::size_t find_alive_within(PlanePoint q, double r) const;

    // The positions of the k points nearest to q (fewer if the tree is
    // smaller), nearest first.
    void nearest(PlanePoint q, std::size_t k, std::vector<std::size_t> &out) const;

    // max over each subtree of value[position]: per-subtree aggregates for
    // walk(), stored by split position.
    template <class T>
    std::vector<T> subtree_max(std::span<const T> value) const
    {
        std::vector<T> result(points_.size());
        if (!points_.empty())
            subtree_max(0, points_.size(), value, result);
        return result;
    }

    // Depth-first walk: enter(split position, box) says whether a subtree may
    // hold anything wanted; visit(position) is called for every point of the
    // subtrees entered.
    template <class Enter, class Visit>
    void walk(Enter &&enter, Visit &&visit) const
    {
        walk(0, points_.size(), enter, visit);
    }

    const Box &box(std::size_t split) const { return box_[split]; }

private:
    template <class Enter, class Visit>
    void walk(std::size_t lo, std::size_t hi, Enter &enter, Visit &visit) const
    {
        if (lo >= hi)
            return;
        const std::size_t mid = lo + (hi - lo) / 2;
        if (!enter(mid, box_[mid]))
            return;
        visit(mid);
        walk(lo, mid, enter, visit);
        walk(mid + 1, hi, enter, visit);
    }

    template <class T>
    void subtree_max(std::size_t lo, std::size_t hi, std::span<const T> value, std::vector<T> &result) const
    {
        const std::size_t mid = lo + (hi - lo) / 2;
        T m = value[mid];
        if (lo < mid) {
            subtree_max(lo, mid, value, result);
            m = std::max(m, result[lo + (mid - lo) / 2]);
        }
        if (mid + 1 < hi) {
            subtree_max(mid + 1, hi, value, result);
            m = std::max(m, result[mid + 1 + (hi - mid - 1) / 2]);
        }
        result[mid] = m;
    }

    void build(std::size_t lo, std::size_t hi, uint32_t parent);
    std::size_t find(std::size_t lo, std::size_t hi, PlanePoint q, double r) const;

    std::vector<PlanePoint> points_;
    std::vector<uint32_t> ids_;
    std::vector<Box> box_;
    std::vector<uint32_t> parent_;       // split position of the parent subtree
    std::vector<uint32_t> alive_count_;  // alive points in the subtree
    std::vector<uint8_t> alive_;
};

} // namespace arbor::topology
