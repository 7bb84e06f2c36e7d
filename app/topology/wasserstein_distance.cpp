#include "wasserstein_distance.hpp"

#include "matching_costs.hpp"

// Only LEMON's templates: no link to its library.
#define LEMON_ONLY_TEMPLATES
#include <lemon/network_simplex.h>
#include <lemon/smart_graph.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace arbor::topology {

namespace {

// Worthwhile pairs listed up front when there are at most this many (about
// 100 bytes each while solved); beyond, the pairs are generated as needed.
constexpr std::size_t kListedPairs = std::size_t{1} << 23;
// Pairs each point starts with when generated: its nearest points of the
// other diagram.
constexpr std::size_t kNearest = 8;
// Pairs a pricing round adds per point at most (the most negative first).
constexpr std::size_t kPricedPerPoint = 16;

// Identical points as one node with their multiplicity.
struct Distinct {
    std::vector<PlanePoint> points;
    std::vector<int64_t> count;
    int64_t total = 0;
};

Distinct distinct_off_diagonal(std::span<const PlanePoint> in)
{
    std::vector<PlanePoint> sorted;
    sorted.reserve(in.size());
    for (const PlanePoint &p : in)
        if (p.y != p.x) // on the diagonal: goes to it at no cost
            sorted.push_back(p);
    std::sort(sorted.begin(), sorted.end(),
              [](const PlanePoint &l, const PlanePoint &r) { return l.x < r.x || (l.x == r.x && l.y < r.y); });
    Distinct d;
    for (const PlanePoint &p : sorted) {
        if (!d.points.empty() && d.points.back().x == p.x && d.points.back().y == p.y) {
            ++d.count.back();
        } else {
            d.points.push_back(p);
            d.count.push_back(1);
        }
        ++d.total;
    }
    return d;
}

// A pair a_i - b_j with its gain: cost(a_i, b_j) - diag(a_i) - diag(b_j),
// negative for a pair worth matching.
struct Pair {
    uint32_t i, j;
    int64_t gain;
};

// The problem in the form the solver gets: everything starts on the diagonal
// (cost: the sum of all diagonal costs), and matching a_i to b_j adds its
// gain.  So the optimum is the sum of diagonal costs plus a maximum-weight
// b-matching (weights -gain, capacities the multiplicities), solved as a
// min-cost flow: source -> a_i (capacity its multiplicity), a_i -> b_j (the
// gain), b_j -> sink (capacity), source -> sink (what stays unmatched).
// Unlike the transport form with one diagonal node per side, points left on
// the diagonal carry no flow, which keeps the network simplex's spanning
// tree from becoming a star that every pivot reshapes.
struct Matching {
    int64_t gain = 0;                     // the optimum's total gain
    std::vector<int64_t> flow;            // per pair
    std::vector<int64_t> potential_a, potential_b; // per point of the network
    int64_t potential_source = 0, potential_sink = 0;
};

using Graph = lemon::SmartDigraph;
using Simplex = lemon::NetworkSimplex<Graph, int64_t, int64_t>;

// The optimal matching over the pairs given; points are a's and b's indices,
// pairs refer to positions in them.
Matching solve(const std::vector<uint32_t> &a_ids, const std::vector<uint32_t> &b_ids,
               const std::vector<Pair> &pairs, const Distinct &a, const Distinct &b, bool potentials)
{
    Graph g;
    g.reserveNode(static_cast<int>(a_ids.size() + b_ids.size() + 2));
    g.reserveArc(static_cast<int>(a_ids.size() + b_ids.size() + pairs.size() + 1));
    Graph::ArcMap<int64_t> cost(g), capacity(g);
    Graph::NodeMap<int64_t> supply(g, 0);
    const Graph::Node source = g.addNode(), sink = g.addNode();
    std::vector<Graph::Node> a_node, b_node;
    int64_t total = 0;
    for (uint32_t i : a_ids) {
        a_node.push_back(g.addNode());
        const Graph::Arc e = g.addArc(source, a_node.back());
        cost[e] = 0;
        capacity[e] = a.count[i];
        total += a.count[i];
    }
    for (uint32_t j : b_ids) {
        b_node.push_back(g.addNode());
        const Graph::Arc e = g.addArc(b_node.back(), sink);
        cost[e] = 0;
        capacity[e] = b.count[j];
    }
    const Graph::Arc unmatched = g.addArc(source, sink);
    cost[unmatched] = 0;
    capacity[unmatched] = total;
    std::vector<Graph::Arc> pair_arc;
    pair_arc.reserve(pairs.size());
    for (const Pair &p : pairs) {
        pair_arc.push_back(g.addArc(a_node[p.i], b_node[p.j]));
        cost[pair_arc.back()] = p.gain;
        capacity[pair_arc.back()] = total;
    }
    supply[source] = total;
    supply[sink] = -total;
    Simplex simplex(g);
    simplex.costMap(cost).upperMap(capacity).supplyMap(supply);
    if (simplex.run() != Simplex::OPTIMAL)
        throw std::logic_error("the matching network has no optimal flow (it always has one)");
    Matching m;
    m.gain = simplex.totalCost();
    m.flow.reserve(pairs.size());
    for (const Graph::Arc &e : pair_arc)
        m.flow.push_back(simplex.flow(e));
    if (potentials) {
        for (const Graph::Node &n : a_node)
            m.potential_a.push_back(simplex.potential(n));
        for (const Graph::Node &n : b_node)
            m.potential_b.push_back(simplex.potential(n));
        m.potential_source = simplex.potential(source);
        m.potential_sink = simplex.potential(sink);
    }
    return m;
}

// Union-find over the points of both diagrams (b_j is na + j).
struct Components {
    std::vector<uint32_t> parent;
    explicit Components(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t x)
    {
        while (parent[x] != x)
            x = parent[x] = parent[parent[x]];
        return x;
    }
    void join(uint32_t x, uint32_t y) { parent[find(x)] = find(y); }
};

class Solver {
public:
    Solver(const Distinct &a, const Distinct &b, double p)
        : a_(a), b_(b), costs_(a.points, b.points, p, a.points.size() + b.points.size() + 2), b_tree_(b.points)
    {
        diag_a_.resize(a.points.size());
        diag_b_.resize(b.points.size());
        for (std::size_t i = 0; i < diag_a_.size(); ++i)
            diag_a_[i] = costs_.of_diagonal(a.points[i]);
        for (std::size_t j = 0; j < diag_b_.size(); ++j)
            diag_b_[j] = costs_.of_diagonal(b.points[j]);
        std::vector<int64_t> by_position(diag_b_.size());
        for (std::size_t pos = 0; pos < by_position.size(); ++pos)
            by_position[pos] = diag_b_[b_tree_.id(pos)];
        max_diag_b_ = b_tree_.subtree_max<int64_t>(by_position);
    }

    WassersteinResult run(double p)
    {
        std::vector<Pair> pairs;
        if (list_worthwhile(pairs))
            by_components(pairs);
        else
            by_generation();
        return result(p);
    }

private:
    int64_t gain(std::size_t i, std::size_t j) const
    {
        return costs_.of_distance(linf_distance(a_.points[i], b_.points[j])) - diag_a_[i] - diag_b_[j];
    }

    // Every pair with a negative gain (a pair with gain >= 0 is never needed:
    // both points to the diagonal cost no more), unless there are more than
    // kListedPairs.  The walk skips subtrees of B whose nearest corner is
    // already too far to gain anything.
    bool list_worthwhile(std::vector<Pair> &pairs) const
    {
        for (std::size_t i = 0; i < a_.points.size(); ++i) {
            const PlanePoint q = a_.points[i];
            bool full = false;
            b_tree_.walk(
                [&](std::size_t split, const PlanePointTree::Box &box) {
                    return !full && costs_.of_distance(box.distance_from(q)) < diag_a_[i] + max_diag_b_[split];
                },
                [&](std::size_t pos) {
                    const uint32_t j = b_tree_.id(pos);
                    const int64_t g = gain(i, j);
                    if (g < 0) {
                        pairs.push_back({static_cast<uint32_t>(i), j, g});
                        full = pairs.size() > kListedPairs;
                    }
                });
            if (full)
                return false;
        }
        return true;
    }

    // The worthwhile pairs split into connected components, each an
    // independent matching problem, solved once: exact with nothing left out.
    void by_components(const std::vector<Pair> &pairs)
    {
        const std::size_t na = a_.points.size();
        Components comp(na + b_.points.size());
        for (const Pair &p : pairs)
            comp.join(p.i, static_cast<uint32_t>(na + p.j));
        std::vector<std::vector<Pair>> pairs_of(na + b_.points.size());
        for (const Pair &p : pairs)
            pairs_of[comp.find(p.i)].push_back(p);
        std::vector<int32_t> local(na + b_.points.size(), -1);
        for (std::vector<Pair> &list : pairs_of) {
            if (list.empty())
                continue;
            std::vector<uint32_t> a_ids, b_ids;
            for (Pair &p : list) {
                if (local[p.i] < 0) {
                    local[p.i] = static_cast<int32_t>(a_ids.size());
                    a_ids.push_back(p.i);
                }
                if (local[na + p.j] < 0) {
                    local[na + p.j] = static_cast<int32_t>(b_ids.size());
                    b_ids.push_back(p.j);
                }
            }
            std::vector<Pair> local_pairs;
            local_pairs.reserve(list.size());
            for (const Pair &p : list)
                local_pairs.push_back({static_cast<uint32_t>(local[p.i]), static_cast<uint32_t>(local[na + p.j]), p.gain});
            const Matching m = solve(a_ids, b_ids, local_pairs, a_, b_, false);
            record(m, list);
            ++solves_;
            arcs_ += list.size();
        }
    }

    // Too many worthwhile pairs to list (real-valued noise): column
    // generation.  The network holds the pairs found so far and the points
    // they touch; the others stay on the diagonal.  After each solve a walk
    // over B finds, for every point of A, the pairs whose reduced cost under
    // the solver's potentials is negative; when there is none the potentials
    // (with sink's potential for B's points outside the network and source's
    // for A's) are a feasible dual of the whole problem and the matching is
    // optimal.
    void by_generation()
    {
        const std::size_t na = a_.points.size(), nb = b_.points.size();
        std::vector<std::vector<uint32_t>> pairs_of(na);
        const auto add = [&](std::size_t i, uint32_t j) {
            std::vector<uint32_t> &list = pairs_of[i];
            if (std::find(list.begin(), list.end(), j) != list.end())
                return false;
            list.push_back(j);
            return true;
        };
        std::vector<std::size_t> near;
        for (std::size_t i = 0; i < na; ++i) {
            b_tree_.nearest(a_.points[i], kNearest, near);
            for (std::size_t pos : near)
                if (gain(i, b_tree_.id(pos)) < 0)
                    add(i, b_tree_.id(pos));
        }
        const PlanePointTree a_tree(a_.points);
        for (std::size_t j = 0; j < nb; ++j) {
            a_tree.nearest(b_.points[j], kNearest, near);
            for (std::size_t pos : near)
                if (gain(a_tree.id(pos), j) < 0)
                    add(a_tree.id(pos), static_cast<uint32_t>(j));
        }
        for (;;) {
            std::vector<int32_t> local_a(na, -1), local_b(nb, -1);
            std::vector<uint32_t> a_ids, b_ids;
            std::vector<Pair> pairs, local_pairs;
            for (std::size_t i = 0; i < na; ++i)
                for (uint32_t j : pairs_of[i]) {
                    if (local_a[i] < 0) {
                        local_a[i] = static_cast<int32_t>(a_ids.size());
                        a_ids.push_back(static_cast<uint32_t>(i));
                    }
                    if (local_b[j] < 0) {
                        local_b[j] = static_cast<int32_t>(b_ids.size());
                        b_ids.push_back(j);
                    }
                    pairs.push_back({static_cast<uint32_t>(i), j, gain(i, j)});
                    local_pairs.push_back({static_cast<uint32_t>(local_a[i]), static_cast<uint32_t>(local_b[j]),
                                           pairs.back().gain});
                }
            const Matching m = solve(a_ids, b_ids, local_pairs, a_, b_, true);
            ++solves_;

            std::vector<int64_t> pi_b(nb, m.potential_sink);
            for (std::size_t k = 0; k < b_ids.size(); ++k)
                pi_b[b_ids[k]] = m.potential_b[k];
            std::vector<int64_t> pi_b_by_position(nb), diag_plus_pi(nb);
            for (std::size_t pos = 0; pos < nb; ++pos) {
                pi_b_by_position[pos] = pi_b[b_tree_.id(pos)];
                diag_plus_pi[pos] = pi_b_by_position[pos] + diag_b_[b_tree_.id(pos)];
            }
            // Reduced cost of a_i -> b_j: cost - diag_a - diag_b + pi_a - pi_b;
            // a subtree can hold a negative one only if its nearest corner's
            // cost is below diag_a - pi_a + max(diag_b + pi_b).
            const std::vector<int64_t> max_diag_plus_pi = b_tree_.subtree_max<int64_t>(diag_plus_pi);
            std::size_t added = 0;
            std::vector<std::pair<int64_t, uint32_t>> negative;
            for (std::size_t i = 0; i < na; ++i) {
                const PlanePoint q = a_.points[i];
                const int64_t pi_a = local_a[i] < 0 ? m.potential_source : m.potential_a[local_a[i]];
                negative.clear();
                b_tree_.walk(
                    [&](std::size_t split, const PlanePointTree::Box &box) {
                        const int64_t bound = costs_.of_distance(box.distance_from(q));
                        return bound < diag_a_[i] + max_diag_b_[split] &&
                               bound - diag_a_[i] + pi_a < max_diag_plus_pi[split];
                    },
                    [&](std::size_t pos) {
                        const uint32_t j = b_tree_.id(pos);
                        const int64_t g = gain(i, j);
                        const int64_t reduced = g + pi_a - pi_b_by_position[pos];
                        if (g < 0 && reduced < 0 &&
                            std::find(pairs_of[i].begin(), pairs_of[i].end(), j) == pairs_of[i].end())
                            negative.emplace_back(reduced, j);
                    });
                if (negative.size() > kPricedPerPoint) {
                    std::nth_element(negative.begin(), negative.begin() + kPricedPerPoint, negative.end());
                    negative.resize(kPricedPerPoint);
                }
                for (const auto &[reduced, j] : negative)
                    added += add(i, j);
            }
            if (added == 0) {
                record(m, pairs);
                arcs_ = pairs.size();
                return;
            }
        }
    }

    void record(const Matching &m, const std::vector<Pair> &pairs)
    {
        gain_ += m.gain;
        for (std::size_t k = 0; k < pairs.size(); ++k) {
            const int64_t f = m.flow[k];
            if (f == 0)
                continue;
            const Pair &p = pairs[k];
            matched_ += f;
            real_gain_ += f * (costs_.real(linf_distance(a_.points[p.i], b_.points[p.j])) -
                               costs_.real(half(a_.points[p.i])) - costs_.real(half(b_.points[p.j])));
        }
    }

    static double half(PlanePoint q) { return (q.y - q.x) * 0.5; }

    WassersteinResult result(double p) const
    {
        int64_t diagonal = 0;
        long double real_diagonal = 0.0L;
        for (const Distinct *d : {&a_, &b_})
            for (std::size_t k = 0; k < d->points.size(); ++k) {
                diagonal += d->count[k] * costs_.of_diagonal(d->points[k]);
                real_diagonal += d->count[k] * costs_.real(half(d->points[k]));
            }
        WassersteinResult r;
        r.exact = costs_.exact();
        r.cost = r.exact ? costs_.to_real(diagonal + gain_) : std::max(0.0L, real_diagonal + real_gain_);
        r.distance = static_cast<double>(std::pow(r.cost, 1.0L / p));
        r.matched_pairs = static_cast<std::size_t>(matched_);
        r.solves = solves_;
        r.arcs = arcs_;
        if (!r.exact) {
            // Every point is charged one rounded cost (error <= 1/(2S)) - its
            // diagonal or its pair's - so this matching is within units/S of
            // the optimum in W^p.
            const int64_t units = a_.total + b_.total - matched_;
            const long double gap = units * costs_.resolution();
            const long double lower = std::pow(std::max(0.0L, r.cost - gap), 1.0L / p);
            r.error_bound = static_cast<double>(r.distance - lower);
        }
        return r;
    }

    const Distinct &a_, &b_;
    MatchingCosts costs_;
    PlanePointTree b_tree_;
    std::vector<int64_t> diag_a_, diag_b_, max_diag_b_;
    int64_t gain_ = 0, matched_ = 0;
    long double real_gain_ = 0.0L;
    int solves_ = 0;
    std::size_t arcs_ = 0;
};

} // namespace

WassersteinResult wasserstein_distance(std::span<const PlanePoint> a_in, std::span<const PlanePoint> b_in, double p)
{
    if (!(p >= 1.0) || !std::isfinite(p))
        throw std::invalid_argument("the Wasserstein exponent p must be a number >= 1, not " + std::to_string(p));
    const Distinct a = distinct_off_diagonal(a_in), b = distinct_off_diagonal(b_in);
    if (a.points.empty() && b.points.empty())
        return {};
    Solver solver(a, b, p);
    return solver.run(p);
}

} // namespace arbor::topology
