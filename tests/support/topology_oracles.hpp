// topology_oracles.hpp - independent, brute-force answers to the questions the
// topology core (app/topology) answers fast: which vertices the Freudenthal
// triangulation connects, how many components a level set has, which
// persistence pairs the elder rule gives, which voxels a branch's contour
// encloses.  Nothing here uses the core's own neighbour tables or trees, so a
// test that compares the two can fail.
//
// Conventions (ALGORITHMS.md section 1): vertex id = x + nx*(y + ny*z); ties
// broken by simulation of simplicity, a is lower than b iff
// (f(a), a) < (f(b), b).
#pragma once

#include "core/volume.hpp"
#include "topology/contour_tree.hpp"
#include "topology/grid_neighbors.hpp"
#include "topology/merge_tree.hpp"
#include "topology/vertex_order.hpp"

#include <algorithm>
#include <array>
#include <compare>
#include <cstdint>
#include <numeric>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace arbor::test {

using Dims = std::array<int64_t, 3>;

// ---- fields ------------------------------------------------------------------

// A scalar field on a grid, its values as doubles (exact for every voxel type
// the tests use: 8/16-bit integers and float32).
struct GridField {
    Dims dims{1, 1, 1};
    std::vector<double> f;

    uint32_t size() const { return static_cast<uint32_t>(f.size()); }
    // Simulation of simplicity.
    bool lower(uint32_t a, uint32_t b) const { return f[a] < f[b] || (f[a] == f[b] && a < b); }
    uint32_t id(int64_t x, int64_t y, int64_t z) const
    {
        return static_cast<uint32_t>(x + dims[0] * (y + dims[1] * z));
    }
    std::array<int64_t, 3> coords(uint32_t v) const
    {
        return {v % dims[0], (v / dims[0]) % dims[1], v / (dims[0] * dims[1])};
    }
};

inline GridField field_of(const Volume &volume)
{
    GridField field;
    field.dims = volume.geometry().dims;
    field.f.resize(static_cast<std::size_t>(volume.voxel_count()));
    for (std::size_t v = 0; v < field.f.size(); ++v)
        field.f[v] = volume.value(static_cast<int64_t>(v));
    return field;
}

// A volume of `type` holding `values` (x fastest); values must be exactly
// representable in the type.
inline Volume make_volume(arbor_voxel_type type, const Dims &dims, const std::vector<double> &values,
                          const std::array<double, 3> &spacing = {1.0, 1.0, 1.0})
{
    Geometry g;
    g.dims = dims;
    g.spacing = spacing;
    Volume volume = Volume::allocate(type, g, {}, uint64_t{1} << 30);
    if (values.size() != static_cast<std::size_t>(volume.voxel_count()))
        throw std::invalid_argument("make_volume: wrong number of values");
    for (std::size_t i = 0; i < values.size(); ++i) {
        switch (type) {
        case ARBOR_VOXEL_U8: volume.as<uint8_t>()[i] = static_cast<uint8_t>(values[i]); break;
        case ARBOR_VOXEL_I8: volume.as<int8_t>()[i] = static_cast<int8_t>(values[i]); break;
        case ARBOR_VOXEL_U16: volume.as<uint16_t>()[i] = static_cast<uint16_t>(values[i]); break;
        case ARBOR_VOXEL_I16: volume.as<int16_t>()[i] = static_cast<int16_t>(values[i]); break;
        case ARBOR_VOXEL_F32: volume.as<float>()[i] = static_cast<float>(values[i]); break;
        case ARBOR_VOXEL_F64: volume.as<double>()[i] = values[i]; break;
        default: throw std::invalid_argument("make_volume: unsupported voxel type");
        }
        if (volume.value(static_cast<int64_t>(i)) != values[i])
            throw std::invalid_argument("make_volume: value " + std::to_string(values[i]) +
                                        " is not representable");
    }
    return volume;
}

// ---- the Freudenthal triangulation, from first principles ------------------------

// The top-dimensional simplices of the grid.  Every cell (a box over the axes
// whose extent is more than one voxel) is cut into k! simplices that share the
// cell's diagonal from its corner (1,0,0) to (0,1,1), i.e. along (-1,1,1), as
// TTK's implicit triangulation does.  Each simplex is a monotone lattice path
// along that diagonal: start at the corner, take one unit step per active axis
// (-x, +y, +z) in one of the k! orders.  Degenerate grids (an axis of extent
// 1) give the triangulation of the face, 2D or 1D; a 1x1x1 grid gives one
// vertex.
inline std::vector<std::vector<uint32_t>> freudenthal_simplices(const Dims &dims)
{
    std::vector<int> axes;
    for (int a = 0; a < 3; ++a)
        if (dims[a] > 1)
            axes.push_back(a);
    const auto id = [&](const std::array<int64_t, 3> &p) {
        return static_cast<uint32_t>(p[0] + dims[0] * (p[1] + dims[1] * p[2]));
    };
    std::vector<std::vector<uint32_t>> simplices;
    const int64_t cx = std::max<int64_t>(dims[0] - 1, 1), cy = std::max<int64_t>(dims[1] - 1, 1),
                  cz = std::max<int64_t>(dims[2] - 1, 1);
    for (int64_t z = 0; z < cz; ++z)
        for (int64_t y = 0; y < cy; ++y)
            for (int64_t x = 0; x < cx; ++x) {
                std::array<int64_t, 3> start{x, y, z};
                if (dims[0] > 1)
                    start[0] += 1; // the diagonal leaves the cell's (1,0,0) corner
                std::vector<int> order = axes;
                do {
                    std::vector<uint32_t> simplex{id(start)};
                    std::array<int64_t, 3> p = start;
                    for (int a : order) {
                        p[a] += a == 0 ? -1 : 1;
                        simplex.push_back(id(p));
                    }
                    simplices.push_back(std::move(simplex));
                } while (std::next_permutation(order.begin(), order.end()));
            }
    return simplices;
}

using Edge = std::array<uint32_t, 2>;
using Triangle = std::array<uint32_t, 3>;

// Every edge of the triangulation once, (low id, high id), sorted.
inline std::vector<Edge> simplex_edges(const std::vector<std::vector<uint32_t>> &simplices)
{
    std::vector<Edge> edges;
    for (const auto &s : simplices)
        for (std::size_t i = 0; i < s.size(); ++i)
            for (std::size_t j = i + 1; j < s.size(); ++j)
                edges.push_back({std::min(s[i], s[j]), std::max(s[i], s[j])});
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

// Every triangle of the triangulation once, vertex ids ascending, sorted.
inline std::vector<Triangle> simplex_triangles(const std::vector<std::vector<uint32_t>> &simplices)
{
    std::vector<Triangle> triangles;
    for (const auto &s : simplices)
        for (std::size_t i = 0; i < s.size(); ++i)
            for (std::size_t j = i + 1; j < s.size(); ++j)
                for (std::size_t k = j + 1; k < s.size(); ++k) {
                    Triangle t{s[i], s[j], s[k]};
                    std::sort(t.begin(), t.end());
                    triangles.push_back(t);
                }
    std::sort(triangles.begin(), triangles.end());
    triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
    return triangles;
}

// The neighbour offsets of an interior vertex: the edges of one unit cube's
// six tetrahedra, in both directions (14 of them).
inline std::vector<std::array<int, 3>> freudenthal_offsets()
{
    const Dims cube{2, 2, 2};
    std::set<std::array<int, 3>> offsets;
    for (const Edge &e : simplex_edges(freudenthal_simplices(cube))) {
        const auto c = [](uint32_t v) { return std::array<int, 3>{int(v % 2), int(v / 2 % 2), int(v / 4)}; };
        const auto a = c(e[0]), b = c(e[1]);
        offsets.insert({b[0] - a[0], b[1] - a[1], b[2] - a[2]});
        offsets.insert({a[0] - b[0], a[1] - b[1], a[2] - b[2]});
    }
    return {offsets.begin(), offsets.end()};
}

// Neighbour lists of every vertex (compressed rows), from the tetrahedra's
// edge offsets clipped to the grid.  (The unit tests check that this equals
// the edge set of freudenthal_simplices on every grid shape.)
struct Adjacency {
    std::vector<uint32_t> begin; // [n + 1]
    std::vector<uint32_t> list;

    template <class F>
    void for_each(uint32_t v, F &&f) const
    {
        for (uint32_t i = begin[v]; i < begin[v + 1]; ++i)
            f(list[i]);
    }
};

inline Adjacency freudenthal_adjacency(const Dims &dims)
{
    static const std::vector<std::array<int, 3>> offsets = freudenthal_offsets();
    const int64_t n = dims[0] * dims[1] * dims[2];
    Adjacency adj;
    adj.begin.reserve(static_cast<std::size_t>(n) + 1);
    adj.list.reserve(static_cast<std::size_t>(n) * 14);
    adj.begin.push_back(0);
    for (int64_t z = 0; z < dims[2]; ++z)
        for (int64_t y = 0; y < dims[1]; ++y)
            for (int64_t x = 0; x < dims[0]; ++x) {
                for (const auto &o : offsets) {
                    const int64_t a = x + o[0], b = y + o[1], c = z + o[2];
                    if (a >= 0 && a < dims[0] && b >= 0 && b < dims[1] && c >= 0 && c < dims[2])
                        adj.list.push_back(static_cast<uint32_t>(a + dims[0] * (b + dims[1] * c)));
                }
                adj.begin.push_back(static_cast<uint32_t>(adj.list.size()));
            }
    return adj;
}

// ---- level sets --------------------------------------------------------------

// Union-find with path halving.
class DisjointSets {
public:
    explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
    uint32_t find(uint32_t x)
    {
        while (parent_[x] != x) {
            parent_[x] = parent_[parent_[x]];
            x = parent_[x];
        }
        return x;
    }
    void unite(uint32_t a, uint32_t b) { parent_[find(a)] = find(b); }
    // Make `root` the representative of a's set (root must be a's root or a
    // root of another set being merged in).
    void attach(uint32_t child_root, uint32_t root) { parent_[child_root] = root; }

private:
    std::vector<uint32_t> parent_;
};

// The triangulation as edges and triangles (by edge index), for counting
// level-set components.
struct LevelSetComplex {
    std::vector<Edge> edges;
    std::vector<std::array<uint32_t, 3>> triangle_edges;
};

inline LevelSetComplex level_set_complex(const Dims &dims)
{
    const auto simplices = freudenthal_simplices(dims);
    LevelSetComplex c;
    c.edges = simplex_edges(simplices);
    const auto edge_index = [&](uint32_t a, uint32_t b) {
        const Edge e{std::min(a, b), std::max(a, b)};
        return static_cast<uint32_t>(std::lower_bound(c.edges.begin(), c.edges.end(), e) - c.edges.begin());
    };
    for (const Triangle &t : simplex_triangles(simplices))
        c.triangle_edges.push_back({edge_index(t[0], t[1]), edge_index(t[1], t[2]), edge_index(t[0], t[2])});
    return c;
}

// Number of connected components of the level set {f = h} of the piecewise
// linear field, for an h equal to no vertex value.  The level set meets every
// edge with one endpoint below h and one above in exactly one point; inside a
// triangle crossed by the level set it is a segment joining the triangle's two
// crossing edges (never one or three: h is no vertex value).  Components are
// therefore the classes of crossing edges under "share a crossed triangle"
// (inside a tetrahedron the level set is a triangle or a quad whose sides lie
// in the tetrahedron's faces, so faces suffice).
inline int brute_force_level_set_components(const LevelSetComplex &c, const GridField &field, double h)
{
    std::vector<char> crossing(c.edges.size());
    for (std::size_t e = 0; e < c.edges.size(); ++e)
        crossing[e] = (field.f[c.edges[e][0]] < h) != (field.f[c.edges[e][1]] < h);
    DisjointSets sets(c.edges.size());
    for (const auto &t : c.triangle_edges) {
        uint32_t first = UINT32_MAX;
        for (uint32_t e : t) {
            if (!crossing[e])
                continue;
            if (first == UINT32_MAX)
                first = e;
            else
                sets.unite(e, first);
        }
    }
    int components = 0;
    for (std::size_t e = 0; e < c.edges.size(); ++e)
        if (crossing[e] && sets.find(static_cast<uint32_t>(e)) == e)
            ++components;
    return components;
}

// ---- persistence pairs by the elder rule ---------------------------------------

struct PairKey {
    int type; // 0 (minimum, join saddle), 2 (split saddle, maximum), -1 (global min, global max)
    uint32_t birth, death;
    auto operator<=>(const PairKey &) const = default;
};

inline std::ostream &operator<<(std::ostream &out, const PairKey &p)
{
    return out << "(" << p.type << ", " << p.birth << ", " << p.death << ")";
}

// The two merge-tree sweeps over the field in simulation-of-simplicity order,
// with union-find over the triangulation's edges.
struct MergeSweeps {
    std::vector<uint32_t> order;            // vertex ids, lowest first
    std::vector<uint8_t> lower_components;  // per vertex: sublevel components it merges (0: minimum)
    std::vector<uint8_t> upper_components;  // per vertex: superlevel components it merges (0: maximum)
    std::vector<PairKey> pairs;             // elder rule, sorted
};

// Sweeping upwards, a vertex whose lower neighbours lie in no component starts
// one (a minimum); one that touches several merges them, and every component
// but the one with the oldest (lowest) minimum dies there: pair (min, v).
// The same downwards for maxima: pair (v, max).  The global minimum and
// maximum never die; they form the essential pair.  Zero-persistence pairs
// (a plateau split by simulation of simplicity) are kept, as TTK keeps them.
inline MergeSweeps elder_rule_sweeps(const GridField &field, const Adjacency &adj)
{
    const uint32_t n = field.size();
    MergeSweeps s;
    s.order.resize(n);
    std::iota(s.order.begin(), s.order.end(), 0u);
    std::sort(s.order.begin(), s.order.end(), [&](uint32_t a, uint32_t b) { return field.lower(a, b); });
    s.lower_components.assign(n, 0);
    s.upper_components.assign(n, 0);

    const auto sweep = [&](bool upward) {
        DisjointSets sets(n);
        std::vector<uint32_t> extremum(n); // per component root: its oldest extremum
        std::vector<char> swept(n, 0);
        for (uint32_t step = 0; step < n; ++step) {
            const uint32_t v = s.order[upward ? step : n - 1 - step];
            std::vector<uint32_t> roots;
            adj.for_each(v, [&](uint32_t w) {
                if (!swept[w])
                    return;
                const uint32_t r = sets.find(w);
                if (std::find(roots.begin(), roots.end(), r) == roots.end())
                    roots.push_back(r);
            });
            (upward ? s.lower_components : s.upper_components)[v] = static_cast<uint8_t>(roots.size());
            swept[v] = 1;
            if (roots.empty()) {
                extremum[v] = v;
                continue;
            }
            // The survivor: the component with the oldest extremum (lowest
            // minimum upwards, highest maximum downwards).
            uint32_t survivor = roots[0];
            for (uint32_t r : roots) {
                const bool older = upward ? field.lower(extremum[r], extremum[survivor])
                                          : field.lower(extremum[survivor], extremum[r]);
                if (older)
                    survivor = r;
            }
            for (uint32_t r : roots) {
                if (r == survivor)
                    continue;
                s.pairs.push_back(upward ? PairKey{0, extremum[r], v} : PairKey{2, v, extremum[r]});
                sets.attach(r, survivor);
            }
            sets.attach(v, survivor);
        }
    };
    sweep(true);
    sweep(false);
    s.pairs.push_back({-1, s.order.front(), s.order.back()});
    std::sort(s.pairs.begin(), s.pairs.end());
    return s;
}

inline std::vector<PairKey> elder_rule_pairs(const GridField &field)
{
    return elder_rule_sweeps(field, freudenthal_adjacency(field.dims)).pairs;
}

// ---- regions enclosed by a contour ------------------------------------------------

// The voxels of the region enclosed by the contour through `saddle` on the
// side of `extremum` (above the saddle for a maximum's branch, below it for a
// minimum's), saddle included: the component U of {v beyond the saddle}
// (simulated order) that holds the extremum, plus every pocket that U encloses
// (a pit inside a peak, a bump inside a basin): the components of the rest of
// the volume other than the one the saddle lies in.  Computed by flooding the
// grid, independently of any contour tree.
inline std::vector<uint32_t> enclosed_region(const GridField &field, const Adjacency &adj, uint32_t saddle,
                                             uint32_t extremum, bool above)
{
    const uint32_t n = field.size();
    const auto beyond = [&](uint32_t v) { return above ? field.lower(saddle, v) : field.lower(v, saddle); };
    std::vector<char> in_u(n, 0), outside(n, 0);
    std::vector<uint32_t> stack{extremum};
    in_u[extremum] = 1;
    while (!stack.empty()) {
        const uint32_t v = stack.back();
        stack.pop_back();
        adj.for_each(v, [&](uint32_t w) {
            if (!in_u[w] && beyond(w)) {
                in_u[w] = 1;
                stack.push_back(w);
            }
        });
    }
    stack.push_back(saddle);
    outside[saddle] = 1;
    while (!stack.empty()) {
        const uint32_t v = stack.back();
        stack.pop_back();
        adj.for_each(v, [&](uint32_t w) {
            if (!in_u[w] && !outside[w]) {
                outside[w] = 1;
                stack.push_back(w);
            }
        });
    }
    std::vector<uint32_t> region;
    for (uint32_t v = 0; v < n; ++v)
        if (!outside[v] || v == saddle)
            region.push_back(v);
    return region;
}

// The node index of every vertex, -1 for regular vertices.
inline std::vector<int64_t> node_of_vertices(const topology::ContourTree &tree)
{
    std::vector<int64_t> node(tree.vertex_arc.size(), -1);
    for (uint32_t x = 0; x < tree.node_count(); ++x)
        node[tree.node_vertex[x]] = x;
    return node;
}

// ---- the core's contour tree, stage by stage ---------------------------------------

// The contour tree exactly as the pipeline's first three stages build it (sort,
// join and split sweeps, merge), without the branch decomposition, so that
// tree-level properties can be checked even where a later stage fails.  The
// sweeps run one after the other, both keeping their components in the merge's
// label words, as the pipeline does when memory is short; compute_topology (with
// no memory budget) runs them at once, so comparing the two compares both
// ways of sweeping.  With `piece` > 0 (8- and 16-bit volumes) the order is
// streamed in pieces of that many vertices, as for a whole-body CT.
inline topology::ContourTree staged_contour_tree(const Volume &volume, uint32_t piece = 0)
{
    using namespace topology;
    const Geometry &g = volume.geometry();
    const uint32_t n = static_cast<uint32_t>(volume.voxel_count());
    OrderPieces order = piece > 0 ? OrderPieces(volume.type(), volume.data(), n, piece)
                                  : OrderPieces(sort_vertices(volume.type(), volume.data(), n));
    const GridNeighbors grid(g.dims[0], g.dims[1], g.dims[2]);
    UninitializedBuffer<MergeVertex> state(n);
    UninitializedBuffer<uint32_t> labels(n);
    compute_join_tree(grid, order, state.data(), labels.data());
    compute_split_tree(grid, order, state.data(), labels.data());
    return merge_contour_tree(std::move(state), std::move(labels), std::move(order));
}

} // namespace arbor::test
