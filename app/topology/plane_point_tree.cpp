#include "plane_point_tree.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>

namespace arbor::topology {

namespace {

constexpr uint32_t kNoParent = std::numeric_limits<uint32_t>::max();

} // namespace

double PlanePointTree::Box::distance_from(PlanePoint q) const
{
    // Each difference is one a point of the box would give at least
    // (rounding is monotone), so the result never exceeds linf_distance.
    double d = 0.0;
    if (x0 > q.x)
        d = std::max(d, x0 - q.x);
    else if (q.x > x1)
        d = std::max(d, q.x - x1);
    if (y0 > q.y)
        d = std::max(d, y0 - q.y);
    else if (q.y > y1)
        d = std::max(d, q.y - y1);
    return d;
}

PlanePointTree::PlanePointTree(std::span<const PlanePoint> points)
{
    std::vector<uint32_t> all(points.size());
    std::iota(all.begin(), all.end(), 0u);
    *this = PlanePointTree(points, all);
}

PlanePointTree::PlanePointTree(std::span<const PlanePoint> points, std::span<const uint32_t> ids)
    : ids_(ids.begin(), ids.end())
{
    points_.resize(ids_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i)
        points_[i] = points[ids_[i]];
    box_.resize(points_.size());
    parent_.resize(points_.size());
    alive_count_.resize(points_.size());
    alive_.assign(points_.size(), 1);
    build(0, points_.size(), kNoParent);
}

void PlanePointTree::build(std::size_t lo, std::size_t hi, uint32_t parent)
{
    if (lo >= hi)
        return;
    Box b{points_[lo].x, points_[lo].x, points_[lo].y, points_[lo].y};
    for (std::size_t i = lo + 1; i < hi; ++i) {
        b.x0 = std::min(b.x0, points_[i].x);
        b.x1 = std::max(b.x1, points_[i].x);
        b.y0 = std::min(b.y0, points_[i].y);
        b.y1 = std::max(b.y1, points_[i].y);
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    // Split the wider side at its median; points and ids move together.
    std::vector<std::size_t> order(hi - lo);
    std::iota(order.begin(), order.end(), lo);
    const bool by_x = b.x1 - b.x0 >= b.y1 - b.y0;
    const auto less = [&](std::size_t i, std::size_t j) {
        const PlanePoint &p = points_[i], &q = points_[j];
        return by_x ? (p.x < q.x || (p.x == q.x && p.y < q.y)) : (p.y < q.y || (p.y == q.y && p.x < q.x));
    };
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(mid - lo), order.end(), less);
    std::vector<PlanePoint> p(order.size());
    std::vector<uint32_t> id(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        p[i] = points_[order[i]];
        id[i] = ids_[order[i]];
    }
    std::copy(p.begin(), p.end(), points_.begin() + static_cast<std::ptrdiff_t>(lo));
    std::copy(id.begin(), id.end(), ids_.begin() + static_cast<std::ptrdiff_t>(lo));
    box_[mid] = b;
    parent_[mid] = parent;
    alive_count_[mid] = static_cast<uint32_t>(hi - lo);
    build(lo, mid, static_cast<uint32_t>(mid));
    build(mid + 1, hi, static_cast<uint32_t>(mid));
}

void PlanePointTree::revive_all()
{
    std::fill(alive_.begin(), alive_.end(), 1);
    // The subtree sizes again: each position's subtree spans [lo, hi).
    struct Range {
        std::size_t lo, hi;
    };
    std::vector<Range> stack{{0, points_.size()}};
    while (!stack.empty()) {
        const Range r = stack.back();
        stack.pop_back();
        if (r.lo >= r.hi)
            continue;
        const std::size_t mid = r.lo + (r.hi - r.lo) / 2;
        alive_count_[mid] = static_cast<uint32_t>(r.hi - r.lo);
        stack.push_back({r.lo, mid});
        stack.push_back({mid + 1, r.hi});
    }
}

void PlanePointTree::remove(std::size_t position)
{
    if (!alive_[position])
        return;
    alive_[position] = 0;
    for (uint32_t s = static_cast<uint32_t>(position); s != kNoParent; s = parent_[s])
        --alive_count_[s];
}

std::size_t PlanePointTree::find_alive_within(PlanePoint q, double r) const
{
    return find(0, points_.size(), q, r);
}

std::size_t PlanePointTree::find(std::size_t lo, std::size_t hi, PlanePoint q, double r) const
{
    while (lo < hi) {
        const std::size_t mid = lo + (hi - lo) / 2;
        if (alive_count_[mid] == 0 || box_[mid].distance_from(q) > r)
            return npos;
        if (alive_[mid] && linf_distance(q, points_[mid]) <= r)
            return mid;
        const std::size_t left = find(lo, mid, q, r);
        if (left != npos)
            return left;
        lo = mid + 1; // the right subtree, iteratively
    }
    return npos;
}

void PlanePointTree::nearest(PlanePoint q, std::size_t k, std::vector<std::size_t> &out) const
{
    out.clear();
    if (k == 0 || points_.empty())
        return;
    // A max-heap of the best k so far: (distance, position).
    std::priority_queue<std::pair<double, std::size_t>> best;
    struct Range {
        std::size_t lo, hi;
    };
    std::vector<Range> stack{{0, points_.size()}};
    while (!stack.empty()) {
        const Range r = stack.back();
        stack.pop_back();
        if (r.lo >= r.hi)
            continue;
        const std::size_t mid = r.lo + (r.hi - r.lo) / 2;
        if (best.size() == k && box_[mid].distance_from(q) >= best.top().first)
            continue;
        const double d = linf_distance(q, points_[mid]);
        if (best.size() < k) {
            best.emplace(d, mid);
        } else if (d < best.top().first) {
            best.pop();
            best.emplace(d, mid);
        }
        // The nearer child last, so that it is searched first.
        const Range left{r.lo, mid}, right{mid + 1, r.hi};
        const auto lower_bound = [&](const Range &c) {
            return c.lo < c.hi ? box_[c.lo + (c.hi - c.lo) / 2].distance_from(q) : 0.0;
        };
        if (lower_bound(left) <= lower_bound(right)) {
            stack.push_back(right);
            stack.push_back(left);
        } else {
            stack.push_back(left);
            stack.push_back(right);
        }
    }
    out.resize(best.size());
    for (std::size_t i = best.size(); i-- > 0;) {
        out[i] = best.top().second;
        best.pop();
    }
}

} // namespace arbor::topology
