// Property tests of the topology core on thousands of random small grids
// (1..5 voxels per axis), against brute-force oracles that share no code with
// it (tests/support/topology_oracles.hpp):
//  - the level-set invariant: arcs spanning h = components of {f = h}, counted
//    on the Freudenthal tetrahedra;
//  - the augmentation and node degrees against the two union-find sweeps;
//  - persistence pairs against the elder rule;
//  - branch structure, measures against flooded regions, simplification cuts
//    and labels against their definitions.
// Values mix float32 in [0, 1), u8 in 0..3 (many ties, so simulation of
// simplicity is exercised on plateaus) and i16 with negative values.
//
// A failing property reports how many grids fail and the smallest ones in
// full (dims, type, values), so a failure is a ready-made known-answer case.
// ARBOR_TOPOLOGY_PROPERTY_GRIDS overrides the number of grids.
#include "topology_oracles.hpp"

#include "topology/branch_decomposition.hpp"
#include "topology/contour_tree.hpp"
#include "topology/critical_points.hpp"
#include "topology/grid_neighbors.hpp"
#include "topology/persistence_pairs.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"
#include "topology/tree_regions.hpp"
#include "core/parallel_ranges.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace arbor {
namespace {

using namespace arbor::topology;
using test::Dims;
using test::PairKey;

// ---- random grids ----------------------------------------------------------------------

struct Sample {
    uint64_t seed = 0;
    Volume volume;
    test::GridField field;
    test::Adjacency adjacency;
    test::MergeSweeps sweeps;
    ContourTree staged;                  // the tree from the stages, always
    std::optional<TopologyResult> result; // compute_topology, unless it threw
    std::string error;                   // what it threw
};

std::size_t grid_count()
{
    if (const char *s = std::getenv("ARBOR_TOPOLOGY_PROPERTY_GRIDS"))
        return static_cast<std::size_t>(std::max(1L, std::atol(s)));
    return 2400;
}

// A grid of 1..5 voxels per axis; the seed picks the voxel type and the
// value distribution.
Volume random_volume(uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int64_t> side(1, 5);
    const Dims dims{side(rng), side(rng), side(rng)};
    const std::size_t n = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
    std::vector<double> values(n);
    arbor_voxel_type type = ARBOR_VOXEL_F32;
    switch (seed % 4) {
    case 0: { // generic: float32 in [0, 1)
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (double &v : values)
            v = static_cast<double>(u(rng));
        break;
    }
    case 1: { // plateaus everywhere: u8 in 0..3
        type = ARBOR_VOXEL_U8;
        std::uniform_int_distribution<int> u(0, 3);
        for (double &v : values)
            v = u(rng);
        break;
    }
    case 2: { // signed, few levels: i16 in -2..2
        type = ARBOR_VOXEL_I16;
        std::uniform_int_distribution<int> u(-2, 2);
        for (double &v : values)
            v = u(rng);
        break;
    }
    default: { // signed, wide: i16 in -1000..1000
        type = ARBOR_VOXEL_I16;
        std::uniform_int_distribution<int> u(-1000, 1000);
        for (double &v : values)
            v = u(rng);
        break;
    }
    }
    // Non-unit spacing, so that mm^3 is checked too.
    return test::make_volume(type, dims, values, {0.5, 2.0, 1.25});
}

const std::vector<Sample> &samples()
{
    static const std::vector<Sample> all = [] {
        std::vector<Sample> out(grid_count());
        for (std::size_t i = 0; i < out.size(); ++i) {
            Sample &s = out[i];
            s.seed = 7919 + i;
            s.volume = random_volume(s.seed);
            s.field = test::field_of(s.volume);
            s.adjacency = test::freudenthal_adjacency(s.field.dims);
            s.sweeps = test::elder_rule_sweeps(s.field, s.adjacency);
            // Integer grids stream their order in pieces of 1 to 7 vertices.
            s.staged = test::staged_contour_tree(
                s.volume, orders_by_counting(s.volume.type()) ? static_cast<uint32_t>(1 + s.seed % 7) : 0);
            try {
                s.result = compute_topology(s.volume, persistence_importance());
            } catch (const std::exception &e) {
                s.error = e.what();
            }
        }
        return out;
    }();
    return all;
}

std::string describe(const Sample &s)
{
    std::ostringstream out;
    const Dims &d = s.field.dims;
    out << "seed " << s.seed << ": " << arbor_voxel_type_name(s.volume.type()) << " " << d[0] << "x" << d[1]
        << "x" << d[2] << " values (x fastest) [";
    for (std::size_t v = 0; v < s.field.f.size(); ++v)
        out << (v ? " " : "") << s.field.f[v];
    out << "]";
    return out.str();
}

// Runs `check` on every sample (an empty string: the property holds) and
// reports the failing grids, smallest first.  Properties of the branch
// decomposition need compute_topology's result; grids where it threw are
// counted (and printed) but left to PipelineSucceedsAndBuildsTheStagedTree,
// which fails for them, so that each property reports its own violations.
void for_every_grid(const std::function<std::string(const Sample &)> &check, bool needs_result = false)
{
    struct Failure {
        std::size_t voxels;
        const Sample *sample;
        std::string message;
    };
    std::vector<Failure> failures;
    std::size_t unchecked = 0;
    for (const Sample &s : samples()) {
        if (needs_result && !s.result) {
            ++unchecked;
            continue;
        }
        std::string message;
        try {
            message = check(s);
        } catch (const std::exception &e) {
            message = std::string("exception: ") + e.what();
        }
        if (!message.empty())
            failures.push_back({s.field.f.size(), &s, message});
    }
    if (unchecked > 0)
        std::cout << "[   NOTE   ] " << unchecked << " of " << samples().size()
                  << " grids not checked: compute_topology threw on them\n";
    if (failures.empty())
        return;
    std::stable_sort(failures.begin(), failures.end(),
                     [](const Failure &a, const Failure &b) { return a.voxels < b.voxels; });
    std::ostringstream out;
    out << failures.size() << " of " << samples().size() - unchecked << " random grids fail; the smallest:";
    for (std::size_t i = 0; i < std::min<std::size_t>(3, failures.size()); ++i)
        out << "\n  " << describe(*failures[i].sample) << "\n    " << failures[i].message;
    ADD_FAILURE() << out.str();
}

double value_of_node(const Sample &s, const ContourTree &t, uint32_t node)
{
    return s.field.f[t.node_vertex[node]];
}

// ---- the triangulation ----------------------------------------------------------------

// The tetrahedra derived from the diagonal (-1,1,1) (and their lower-
// dimensional restrictions) have exactly the core's neighbour sets, on every
// grid shape up to 4x4x4; the 14 offsets of an interior vertex are the
// documented ones.
TEST(FreudenthalTriangulation, TetrahedraReproduceTheGridNeighbours)
{
    for (int64_t nz = 1; nz <= 4; ++nz)
        for (int64_t ny = 1; ny <= 4; ++ny)
            for (int64_t nx = 1; nx <= 4; ++nx) {
                const Dims dims{nx, ny, nz};
                const auto edges = test::simplex_edges(test::freudenthal_simplices(dims));
                std::vector<test::Edge> core, clipped;
                const GridNeighbors grid(nx, ny, nz);
                const test::Adjacency adj = test::freudenthal_adjacency(dims);
                for (uint32_t v = 0; v < grid.size(); ++v) {
                    grid.for_each(v, [&](int64_t w) {
                        if (w > v)
                            core.push_back({v, static_cast<uint32_t>(w)});
                    });
                    adj.for_each(v, [&](uint32_t w) {
                        if (w > v)
                            clipped.push_back({v, w});
                    });
                }
                std::sort(core.begin(), core.end());
                std::sort(clipped.begin(), clipped.end());
                EXPECT_EQ(core, edges) << nx << "x" << ny << "x" << nz;
                EXPECT_EQ(clipped, edges) << nx << "x" << ny << "x" << nz;
            }
    std::set<std::array<int, 3>> documented;
    for (const NeighborOffset &o : kFreudenthalOffsets)
        documented.insert({o.di, o.dj, o.dk});
    using Offset = std::array<int, 3>;
    const auto derived = test::freudenthal_offsets();
    EXPECT_EQ(std::set<Offset>(derived.begin(), derived.end()), documented);
    EXPECT_EQ(documented.size(), 14u);
    EXPECT_EQ(documented.count(Offset{-1, 1, 1}), 1u);
    EXPECT_EQ(documented.count(Offset{1, 1, 1}), 0u);
}

// One cube: six tetrahedra of volume 1/6 (|det| = 1), all sharing the
// diagonal from (1,0,0) = vertex 1 to (0,1,1) = vertex 6.
TEST(FreudenthalTriangulation, CubeIsSixTetrahedraAroundTheDiagonal)
{
    const auto tets = test::freudenthal_simplices({2, 2, 2});
    ASSERT_EQ(tets.size(), 6u);
    std::set<std::vector<uint32_t>> distinct;
    for (const auto &t : tets) {
        ASSERT_EQ(t.size(), 4u);
        EXPECT_NE(std::find(t.begin(), t.end(), 1u), t.end());
        EXPECT_NE(std::find(t.begin(), t.end(), 6u), t.end());
        const auto c = [](uint32_t v) { return std::array<int, 3>{int(v % 2), int(v / 2 % 2), int(v / 4)}; };
        std::array<std::array<int, 3>, 3> m{};
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k)
                m[r][k] = c(t[r + 1])[k] - c(t[0])[k];
        const int det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        EXPECT_EQ(std::abs(det), 1);
        std::vector<uint32_t> sorted = t;
        std::sort(sorted.begin(), sorted.end());
        distinct.insert(sorted);
    }
    EXPECT_EQ(distinct.size(), 6u);
    // A 3x3x3 grid: 8 cubes of 6 tetrahedra; a 4x3x1 plane: 6 squares of 2 triangles.
    EXPECT_EQ(test::freudenthal_simplices({3, 3, 3}).size(), 48u);
    EXPECT_EQ(test::freudenthal_simplices({4, 3, 1}).size(), 12u);
    EXPECT_EQ(test::freudenthal_simplices({1, 1, 1}).size(), 1u);
}

// The oracle itself, on hand-counted level sets: a 3x1x1 strip [0 2 0]
// crosses h = 1 twice; a 3x3x1 plane with a centre peak has one closed curve.
TEST(FreudenthalTriangulation, BruteForceLevelSetCountsHandCases)
{
    test::GridField strip{{3, 1, 1}, {0, 2, 0}};
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(strip.dims), strip, 1.0), 2);
    test::GridField peak{{3, 3, 1}, {0, 0, 0, 0, 5, 0, 0, 0, 0}};
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(peak.dims), peak, 1.0), 1);
    // Two interior peaks of a 4x4 plane at (2,1) and (1,2) are neighbours (the
    // 2D diagonal runs along (-1,1)): one curve around both.  At (1,1) and
    // (2,2) they are not: two curves.
    test::GridField antidiagonal{{4, 4, 1}, std::vector<double>(16, 0.0)};
    antidiagonal.f[6] = antidiagonal.f[9] = 5;
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(antidiagonal.dims), antidiagonal, 1.0),
              1);
    test::GridField diagonal{{4, 4, 1}, std::vector<double>(16, 0.0)};
    diagonal.f[5] = diagonal.f[10] = 5;
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(diagonal.dims), diagonal, 1.0), 2);
    // A peak at the corner (1,0) and (0,1) of a 3x3 plane: the band they form
    // cuts the corner (0,0) off, so the level set has two curves.
    test::GridField band{{3, 3, 1}, {0, 5, 0, 5, 0, 0, 0, 0, 0}};
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(band.dims), band, 1.0), 2);
    // In a cube, corners 0 and 7 are not neighbours: two caps.  1 and 6 are:
    // one tube along the body diagonal, whose surface is one annulus.
    test::GridField corners{{2, 2, 2}, {5, 0, 0, 0, 0, 0, 0, 5}};
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(corners.dims), corners, 1.0), 2);
    test::GridField body{{2, 2, 2}, {0, 5, 0, 0, 0, 0, 5, 0}};
    EXPECT_EQ(test::brute_force_level_set_components(test::level_set_complex(body.dims), body, 1.0), 1);
}

// ---- the contour tree ---------------------------------------------------------------------

// For every gap between consecutive distinct values, at its midpoint and at a
// random point inside it, the arcs spanning h (f(lower node) < h < f(upper
// node)) are exactly as many as the components of the level set {f = h}.
TEST(ContourTreeProperties, SpanningArcsCountLevelSetComponents)
{
    for_every_grid([](const Sample &s) -> std::string {
        const ContourTree &t = s.staged;
        std::vector<double> levels = s.field.f;
        std::sort(levels.begin(), levels.end());
        levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
        const test::LevelSetComplex complex = test::level_set_complex(s.field.dims);
        std::mt19937_64 rng(s.seed);
        std::uniform_real_distribution<double> u(0.05, 0.95);
        for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
            for (const double fraction : {0.5, u(rng)}) {
                const double h = levels[i] + fraction * (levels[i + 1] - levels[i]);
                if (!(levels[i] < h && h < levels[i + 1]))
                    continue; // cannot happen for these types; never test on a vertex value
                int spanning = 0;
                for (std::size_t a = 0; a < t.arc_count(); ++a)
                    if (value_of_node(s, t, t.arc_lo[a]) < h && h < value_of_node(s, t, t.arc_hi[a]))
                        ++spanning;
                const int components = test::brute_force_level_set_components(complex, s.field, h);
                if (spanning != components)
                    return "at h = " + std::to_string(h) + ": " + std::to_string(spanning) +
                           " arcs span h, the level set has " + std::to_string(components) + " components";
            }
        }
        return "";
    });
}

// The tree is a tree on the critical vertices, in simulated order, with the
// degrees the two sweeps give (down-degree = sublevel components a vertex
// merges, up-degree = superlevel components), kinds that follow from them,
// and an augmentation that puts every regular vertex strictly inside its arc.
TEST(ContourTreeProperties, NodesDegreesAndAugmentation)
{
    for_every_grid([](const Sample &s) -> std::string {
        const ContourTree &t = s.staged;
        const test::GridField &f = s.field;
        const uint32_t n = f.size();
        std::ostringstream err;
        if (t.vertex_arc.size() != n)
            return "vertex_arc has " + std::to_string(t.vertex_arc.size()) + " entries";
        if (n == 1) {
            if (t.node_count() != 1 || t.node_kind[0] != NodeKind::Lone || t.arc_count() != 0 ||
                t.vertex_arc[0] != kNoArc)
                return "a one-voxel volume must be one lone node without arcs";
            return "";
        }
        if (t.arc_count() + 1 != t.node_count())
            return std::to_string(t.arc_count()) + " arcs for " + std::to_string(t.node_count()) + " nodes";
        // Nodes in simulated order, from the global minimum to the global maximum.
        for (std::size_t i = 0; i + 1 < t.node_count(); ++i)
            if (!f.lower(t.node_vertex[i], t.node_vertex[i + 1]))
                return "nodes " + std::to_string(i) + " and " + std::to_string(i + 1) + " out of order";
        if (t.node_vertex.front() != s.sweeps.order.front() || t.node_vertex.back() != s.sweeps.order.back())
            return "node 0 / the last node are not the global minimum / maximum";
        // Connected: union-find over the arcs.
        test::DisjointSets sets(t.node_count());
        std::vector<int> up(t.node_count(), 0), down(t.node_count(), 0);
        for (std::size_t a = 0; a < t.arc_count(); ++a) {
            if (t.arc_lo[a] >= t.arc_hi[a])
                return "arc " + std::to_string(a) + " does not run upwards";
            sets.unite(t.arc_lo[a], t.arc_hi[a]);
            ++up[t.arc_lo[a]];
            ++down[t.arc_hi[a]];
        }
        for (uint32_t x = 0; x < t.node_count(); ++x)
            if (sets.find(x) != sets.find(0))
                return "the tree is not connected";
        std::vector<char> is_node(n, 0);
        for (uint32_t x = 0; x < t.node_count(); ++x) {
            const uint32_t v = t.node_vertex[x];
            if (is_node[v])
                return "vertex " + std::to_string(v) + " is more than one node";
            is_node[v] = 1;
            if (t.node_up[x] != up[x] || t.node_down[x] != down[x])
                return "node " + std::to_string(x) + ": node_up/node_down disagree with the arcs";
            if (t.node_down[x] != s.sweeps.lower_components[v] || t.node_up[x] != s.sweeps.upper_components[v])
                err << "node vertex " << v << " has " << int(t.node_down[x]) << " arcs down, "
                    << int(t.node_up[x]) << " up; the sweeps give " << int(s.sweeps.lower_components[v])
                    << " and " << int(s.sweeps.upper_components[v]) << "; ";
            const int u = t.node_up[x], d = t.node_down[x];
            NodeKind want = d == 0 ? NodeKind::Minimum
                            : u == 0 ? NodeKind::Maximum
                            : (d >= 2 && u >= 2) ? NodeKind::Saddle
                            : d >= 2 ? NodeKind::JoinSaddle
                                     : NodeKind::SplitSaddle;
            if (u == 1 && d == 1)
                err << "node vertex " << v << " is regular (one arc down, one up); ";
            if (t.node_kind[x] != want)
                err << "node vertex " << v << " is a " << node_kind_name(t.node_kind[x]) << ", expected "
                    << node_kind_name(want) << "; ";
            const uint32_t a = t.vertex_arc[v];
            if (a >= t.arc_count() || (t.arc_lo[a] != x && t.arc_hi[a] != x))
                err << "node vertex " << v << " carries arc " << a << ", which does not touch it; ";
        }
        for (uint32_t v = 0; v < n; ++v) {
            if (is_node[v])
                continue;
            if (s.sweeps.lower_components[v] != 1 || s.sweeps.upper_components[v] != 1)
                err << "vertex " << v << " is critical by the sweeps (" << int(s.sweeps.lower_components[v])
                    << " down, " << int(s.sweeps.upper_components[v]) << " up) but not a node; ";
            const uint32_t a = t.vertex_arc[v];
            if (a >= t.arc_count()) {
                err << "vertex " << v << " has no arc; ";
                continue;
            }
            const uint32_t lo = t.node_vertex[t.arc_lo[a]], hi = t.node_vertex[t.arc_hi[a]];
            if (!f.lower(lo, v) || !f.lower(v, hi))
                err << "vertex " << v << " (" << f.f[v] << ") lies outside its arc " << lo << " (" << f.f[lo]
                    << ") - " << hi << " (" << f.f[hi] << "); ";
        }
        return err.str();
    });
}

// Every voxel is a node or lies inside one arc: the interior counts are the
// regular vertices the augmentation puts on each arc.
TEST(ContourTreeProperties, ArcInteriorVoxelsCountTheRegularVerticesOfEachArc)
{
    for_every_grid([](const Sample &s) -> std::string {
        const ContourTree &t = s.staged;
        const HugeVector<uint32_t> interior = arc_interior_voxels(t);
        if (interior.size() != t.arc_count())
            return std::to_string(interior.size()) + " counts for " + std::to_string(t.arc_count()) + " arcs";
        std::vector<char> is_node(t.vertex_arc.size(), 0);
        for (const uint32_t v : t.node_vertex)
            is_node[v] = 1;
        std::vector<uint32_t> want(t.arc_count(), 0);
        for (uint32_t v = 0; v < t.vertex_arc.size(); ++v)
            if (!is_node[v])
                ++want[t.vertex_arc[v]];
        uint64_t total = t.node_count();
        for (std::size_t a = 0; a < t.arc_count(); ++a) {
            if (interior[a] != want[a])
                return "arc " + std::to_string(a) + ": " + std::to_string(interior[a]) + " interior voxels, " +
                       std::to_string(want[a]) + " regular vertices on it";
            total += interior[a];
        }
        if (total != t.vertex_arc.size())
            return "nodes and interiors add up to " + std::to_string(total) + " of " +
                   std::to_string(t.vertex_arc.size()) + " voxels";
        return "";
    });
}

// Counting extrema vertex by vertex finds exactly the contour tree's
// leaves: its minima and maxima.
TEST(ContourTreeProperties, LocalExtremaAreTheTreesLeaves)
{
    for_every_grid([](const Sample &s) -> std::string {
        const ContourTree &t = s.staged;
        uint64_t minima = 0, maxima = 0;
        for (std::size_t x = 0; x < t.node_count(); ++x) {
            minima += t.node_down[x] == 0;
            maxima += t.node_up[x] == 0;
        }
        const Geometry &g = s.volume.geometry();
        const ExtremumCount c = count_extrema(s.volume.type(), s.volume.data(), g.dims[0], g.dims[1], g.dims[2]);
        if (c.minima != minima || c.maxima != maxima)
            return "counted " + std::to_string(c.minima) + " minima and " + std::to_string(c.maxima) +
                   " maxima, the tree has " + std::to_string(minima) + " and " + std::to_string(maxima);
        return "";
    });
}

// The pipeline (with its shared work space) builds the same tree as the
// stages run one by one, and does not fail on any valid volume.
// The staged tree sweeps one tree after the other in the merge state alone
// (streaming the order in pieces of 1 to 7 vertices on integer grids);
// the pipeline sweeps both at once: the same tree either way.
TEST(ContourTreeProperties, PipelineSucceedsAndBuildsTheStagedTree)
{
    for_every_grid([](const Sample &s) -> std::string {
        if (!s.result)
            return "compute_topology threw: " + s.error;
        const ContourTree &a = s.result->tree, &b = s.staged;
        if (a.node_vertex != b.node_vertex)
            return "different nodes";
        const auto ends = [](const ContourTree &t, uint32_t arc) {
            return arc == kNoArc ? std::pair<uint32_t, uint32_t>{kNoVertex, kNoVertex}
                                 : std::pair{t.node_vertex[t.arc_lo[arc]], t.node_vertex[t.arc_hi[arc]]};
        };
        const std::vector<int64_t> node_of = test::node_of_vertices(b);
        for (uint32_t v = 0; v < b.vertex_arc.size(); ++v)
            if (ends(a, a.vertex_arc[v]) != ends(b, b.vertex_arc[v]) && node_of[v] < 0)
                return "vertex " + std::to_string(v) + " lies on different arcs";
        std::set<std::pair<uint32_t, uint32_t>> arcs_a, arcs_b;
        for (uint32_t x = 0; x < a.arc_count(); ++x)
            arcs_a.insert(ends(a, x));
        for (uint32_t x = 0; x < b.arc_count(); ++x)
            arcs_b.insert(ends(b, x));
        return arcs_a == arcs_b ? "" : "different arcs";
    });
}

// ---- persistence pairs --------------------------------------------------------------------

std::set<PairKey> pairs_of(const Sample &s)
{
    const FieldView view{s.volume.type(), s.volume.data(), s.field.size(), &s.volume.geometry()};
    std::set<PairKey> out;
    for (const PersistencePair &p : persistence_pairs(s.result->tree, s.result->branches, view)) {
        out.insert({p.type, p.birth, p.death});
        if (p.birth_value != s.field.f[p.birth] || p.death_value != s.field.f[p.death])
            throw std::runtime_error("pair values differ from the voxel values");
    }
    return out;
}

std::string difference(const std::set<PairKey> &got, const std::set<PairKey> &want)
{
    std::ostringstream out;
    for (const PairKey &p : got)
        if (!want.count(p))
            out << "extra " << p << " ";
    for (const PairKey &p : want)
        if (!got.count(p))
            out << "missing " << p << " ";
    return out.str();
}

// With persistence, the branch decomposition's pairs are the elder rule's
// pairs of the join and split trees, zero-persistence pairs included.
TEST(PersistencePairProperties, EqualTheElderRulePairs)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const std::set<PairKey> want(s.sweeps.pairs.begin(), s.sweeps.pairs.end());
            if (want.size() != s.sweeps.pairs.size())
                return "the oracle produced a pair twice";
            return difference(pairs_of(s), want);
        },
        true);
}

// ---- branch decomposition -------------------------------------------------------------------

// Tree path (arc indices) between two contour-tree nodes, by breadth-first
// search over the nodes.
std::vector<uint32_t> tree_path(const ContourTree &t, uint32_t from, uint32_t to)
{
    std::vector<uint32_t> via(t.node_count(), kNoArc);
    std::vector<uint8_t> seen(t.node_count(), 0);
    std::vector<uint32_t> queue{from};
    seen[from] = 1;
    for (std::size_t k = 0; k < queue.size() && !seen[to]; ++k) {
        const uint32_t x = queue[k];
        for (uint32_t i = t.node_arc_offsets[x]; i < t.node_arc_offsets[x + 1]; ++i) {
            const uint32_t a = t.node_arcs[i];
            const uint32_t y = t.arc_lo[a] == x ? t.arc_hi[a] : t.arc_lo[a];
            if (!seen[y]) {
                seen[y] = 1;
                via[y] = a;
                queue.push_back(y);
            }
        }
    }
    std::vector<uint32_t> path;
    for (uint32_t x = to; x != from;) {
        const uint32_t a = via[x];
        path.push_back(a);
        x = t.arc_lo[a] == x ? t.arc_hi[a] : t.arc_lo[a];
    }
    return path;
}

// Whether the pairs form a branch decomposition: the tree paths between each
// branch's extremum and saddle (the root's from node 0 to the last node) are
// monotone, pairwise disjoint and cover every arc.  True for every volume of
// the shared data; false for some tiny or thin grids (1 x 1 x n strips, the
// 3 x 2 plane of PlaneWhoseGlobalExtremaAreJoinedByANonMonotonePath), where
// the documented ownership rule applies instead.
bool pairs_form_a_decomposition(const ContourTree &t, const BranchDecomposition &d)
{
    std::vector<int> used(t.arc_count(), 0);
    for (const Branch &b : d.branches) {
        const std::vector<uint32_t> path = tree_path(t, b.saddle_node, b.extremum_node);
        uint32_t x = b.saddle_node;
        const bool up = b.kind != BranchKind::Minimum;
        for (auto it = path.rbegin(); it != path.rend(); ++it) {
            const uint32_t a = *it;
            if (up ? t.arc_lo[a] != x : t.arc_hi[a] != x)
                return false; // not monotone
            x = up ? t.arc_hi[a] : t.arc_lo[a];
            if (++used[a] > 1)
                return false;
        }
    }
    return std::all_of(used.begin(), used.end(), [](int u) { return u == 1; }) || t.arc_count() == 0;
}

// Root first, parents before children, depths, children lists; every arc in
// exactly one branch.  Where the pairs form a branch decomposition, each
// branch's arcs are the monotone path from its saddle to its extremum (the
// root's from node 0 to the last node), a branch's saddle lies on its parent
// (node_branch) and its extremum on itself.
TEST(BranchDecompositionProperties, BranchesAreMonotonePathsCoveringEveryArc)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const ContourTree &t = s.result->tree;
            const BranchDecomposition &d = s.result->branches;
            const auto &bs = d.branches;
            const uint32_t last = static_cast<uint32_t>(t.node_count() - 1);
            if (bs.empty())
                return "no branches";
            const Branch &root = bs[0];
            if (root.kind != BranchKind::Root || root.parent != -1 || root.depth != 0 || root.saddle_node != 0 ||
                root.extremum_node != last || !std::isinf(root.importance))
                return "branch 0 is not the root from node 0 to the last node";
            const bool decomposition = pairs_form_a_decomposition(t, d);
            if (d.arc_branch.size() != t.arc_count() || d.node_branch.size() != t.node_count())
                return "arc_branch/node_branch have the wrong size";
            std::vector<std::vector<uint32_t>> kids(bs.size());
            for (uint32_t b = 1; b < bs.size(); ++b) {
                const Branch &br = bs[b];
                if (br.kind == BranchKind::Root)
                    return "two roots";
                if (br.parent < 0 || static_cast<uint32_t>(br.parent) >= b)
                    return "branch " + std::to_string(b) + " comes before its parent";
                if (br.depth != bs[br.parent].depth + 1)
                    return "branch " + std::to_string(b) + ": depth is not the parent's + 1";
                kids[br.parent].push_back(b);
                const bool up = br.kind == BranchKind::Maximum;
                if (up ? t.node_up[br.extremum_node] != 0 : t.node_down[br.extremum_node] != 0)
                    return "branch " + std::to_string(b) + " does not end at an extremum of its kind";
                if (up ? t.node_up[br.saddle_node] < 2 : t.node_down[br.saddle_node] < 2)
                    return "branch " + std::to_string(b) + "'s saddle has fewer than two arcs on its side";
                if (!decomposition)
                    continue;
                if (d.node_branch[br.saddle_node] != static_cast<uint32_t>(br.parent))
                    return "branch " + std::to_string(b) + "'s saddle does not lie on its parent";
                if (d.node_branch[br.extremum_node] != b)
                    return "branch " + std::to_string(b) + "'s extremum does not lie on it";
            }
            for (uint32_t b = 0; b < bs.size(); ++b) {
                std::vector<uint32_t> c;
                for (const uint32_t child : d.children(b))
                    c.push_back(child);
                if (c != kids[b])
                    return "branch " + std::to_string(b) + ": children list disagrees with the parents";
            }
            // The arcs of each branch, walked from its start.
            std::vector<std::vector<uint32_t>> owned(bs.size());
            for (uint32_t a = 0; a < t.arc_count(); ++a) {
                if (d.arc_branch[a] >= bs.size())
                    return "arc " + std::to_string(a) + " has no branch";
                owned[d.arc_branch[a]].push_back(a);
            }
            if (!decomposition)
                return "";
            for (uint32_t b = 0; b < bs.size(); ++b) {
                const bool up = bs[b].kind != BranchKind::Minimum;
                uint32_t x = bs[b].saddle_node;
                std::vector<uint32_t> left = owned[b];
                while (!left.empty()) {
                    const auto it = std::find_if(left.begin(), left.end(), [&](uint32_t a) {
                        return up ? t.arc_lo[a] == x : t.arc_hi[a] == x;
                    });
                    if (it == left.end())
                        return "branch " + std::to_string(b) + "'s arcs are not a monotone path from its saddle";
                    x = up ? t.arc_hi[*it] : t.arc_lo[*it];
                    left.erase(it);
                }
                if (x != bs[b].extremum_node && t.arc_count() > 0)
                    return "branch " + std::to_string(b) + "'s path does not end at its extremum";
            }
            return "";
        },
        true);
}

// Every branch's measures against those of its region flooded in the grid:
// the saddle plus the voxels enclosed by its contour at the saddle.  The
// root's region is the whole volume.  "" when they all agree.
std::string measures_against_flooding(const Volume &volume, const test::GridField &f, const test::Adjacency &adjacency,
                                      const TopologyResult &result)
{
    const ContourTree &t = result.tree;
    const BranchDecomposition &d = result.branches;
    const auto &bs = d.branches;
    const auto [lo, hi] = std::minmax_element(f.f.begin(), f.f.end());
    const double f_min = *lo, f_max = *hi;
    const Geometry &g = volume.geometry();
    const double mm3 = g.spacing[0] * g.spacing[1] * g.spacing[2];
    std::ostringstream err;
    const auto near = [](double a, double b) { return std::fabs(a - b) <= 1e-9 * (1.0 + std::fabs(b)); };
    std::array<double, kMeasureCount> root{};
    root[kPersistence] = f_max - f_min;
    root[kVolume] = f.size();
    root[kVolumeMm3] = f.size() * mm3;
    for (double v : f.f)
        root[kHypervolume] += v - f_min;
    for (uint32_t b = 0; b < bs.size(); ++b) {
        std::array<double, kMeasureCount> want{};
        if (b == 0) {
            want = root;
            want[kRelativeHypervolume] = bs[b].measures[kRelativeHypervolume];
        } else {
            const uint32_t sv = t.node_vertex[bs[b].saddle_node], ev = t.node_vertex[bs[b].extremum_node];
            const auto region = test::enclosed_region(f, adjacency, sv, ev, bs[b].kind == BranchKind::Maximum);
            want[kPersistence] = std::fabs(f.f[ev] - f.f[sv]);
            want[kVolume] = static_cast<double>(region.size());
            want[kVolumeMm3] = region.size() * mm3;
            for (uint32_t v : region)
                want[kHypervolume] += f.f[v] - f_min;
            want[kRelativeHypervolume] = bs[b].measures[kRelativeHypervolume]; // tested below
        }
        for (int m = 0; m < kMeasureCount; ++m) {
            const double got = bs[b].measures[m];
            if (!near(got, want[m]))
                err << "branch " << b << " " << measure_id(m) << " " << got << ", flooded " << want[m] << "; ";
            const double rel = root[m] > 0 ? want[m] / root[m] : 0.0;
            if (m != kRelativeHypervolume && !near(d.relative(b, m), rel))
                err << "branch " << b << " relative " << measure_id(m) << " " << d.relative(b, m) << ", expected "
                    << rel << "; ";
        }
        if (b > 0 && !near(bs[b].importance, d.relative(b, kPersistence)))
            err << "branch " << b << ": importance is not its relative persistence; ";
    }
    return err.str();
}

TEST(BranchDecompositionProperties, MeasuresMatchFloodedRegions)
{
    for_every_grid(
        [](const Sample &s) { return measures_against_flooding(s.volume, s.field, s.adjacency, *s.result); }, true);
}

// The same on a 16-bit volume large enough that the voxels' sums are split
// between the cores (where there are two or more): smooth bumps whose
// regions straddle the middle slice, where the parts meet.
TEST(BranchDecompositionProperties, MeasuresMatchFloodedRegionsWhenSummedOnSeveralCores)
{
    const Dims dims{96, 64, 100};
    std::vector<double> values(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
    const std::array<std::array<double, 4>, 5> bumps{{// x, y, z, height (negative: a basin)
                                                      {30, 28, 50, 30000},
                                                      {66, 34, 44, 22000},
                                                      {48, 46, 56, -15000},
                                                      {22, 46, 22, 18000},
                                                      {72, 20, 78, 26000}}};
    for (int64_t z = 0; z < dims[2]; ++z)
        for (int64_t y = 0; y < dims[1]; ++y)
            for (int64_t x = 0; x < dims[0]; ++x) {
                double v = 20000 + 50 * z;
                for (const auto &b : bumps) {
                    const double r2 = (x - b[0]) * (x - b[0]) + (y - b[1]) * (y - b[1]) + (z - b[2]) * (z - b[2]);
                    v += b[3] * std::exp(-r2 / (2 * 12.0 * 12.0));
                }
                values[static_cast<std::size_t>(x + dims[0] * (y + dims[1] * z))] = std::round(v);
            }
    const Volume volume = test::make_volume(ARBOR_VOXEL_U16, dims, values);
    const TopologyResult result = compute_topology(volume, persistence_importance());
    ASSERT_GE(result.branches.branches.size(), 5u);
    ASSERT_LE(result.branches.branches.size(), 200u) << "too many branches to flood each";
    std::cout << "[   NOTE   ] " << result.branches.branches.size() << " branches, voxels summed in "
              << range_parts(volume.voxel_count(), kSplitSumsVoxels) << " parts\n";
    const test::GridField field = test::field_of(volume);
    EXPECT_EQ(measures_against_flooding(volume, field, test::freudenthal_adjacency(dims), result), "");
}

// Relative hypervolume as documented: the volume between the function and
// the saddle level over the branch's region, sum of f - f(saddle) for a peak
// and f(saddle) - f for a basin, never below 0 (so the sum of |f - f(saddle)|
// for regions on one side of their saddle level).
TEST(BranchDecompositionProperties, RelativeHypervolumeIsTheVolumeBetweenFunctionAndSaddleLevel)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const ContourTree &t = s.result->tree;
            const auto &bs = s.result->branches.branches;
            std::ostringstream err;
            for (uint32_t b = 1; b < bs.size(); ++b) {
                const uint32_t sv = t.node_vertex[bs[b].saddle_node], ev = t.node_vertex[bs[b].extremum_node];
                const bool peak = bs[b].kind == BranchKind::Maximum;
                double want = 0;
                for (uint32_t v : test::enclosed_region(s.field, s.adjacency, sv, ev, peak))
                    want += peak ? s.field.f[v] - s.field.f[sv] : s.field.f[sv] - s.field.f[v];
                want = std::max(0.0, want);
                const double got = bs[b].measures[kRelativeHypervolume];
                if (std::fabs(got - want) > 1e-9 * (1.0 + want))
                    err << "branch " << b << " (saddle " << sv << ", extremum " << ev << "): " << got
                        << ", expected " << want << "; ";
            }
            return err.str();
        },
        true);
}

// The strong checks above run on the great majority of grids: trees without a
// monotone decomposition of their pairs are the exception.
TEST(BranchDecompositionProperties, MostGridsFormADecomposition)
{
    std::size_t yes = 0, total = 0;
    for (const Sample &s : samples()) {
        if (!s.result)
            continue;
        ++total;
        yes += pairs_form_a_decomposition(s.result->tree, s.result->branches) ? 1 : 0;
    }
    std::cout << "[   NOTE   ] " << yes << " of " << total << " grids form a branch decomposition\n";
    EXPECT_GE(yes * 10, total * 9);
}

// Where the pairs form a branch decomposition, the measures add up over the
// hierarchy: a branch's region is its saddle, the interiors of its own arcs,
// its own nodes, and its children's regions without their saddles (which are
// its own nodes).  Counted from arc_branch, node_branch and vertex_arc alone.
TEST(BranchDecompositionProperties, RegionsAddUpOverTheHierarchy)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const ContourTree &t = s.result->tree;
            const BranchDecomposition &d = s.result->branches;
            const auto &bs = d.branches;
            if (!pairs_form_a_decomposition(t, d))
                return "";
            const double f_min = s.field.f[s.sweeps.order.front()];
            std::vector<double> count(bs.size(), 0.0), sum(bs.size(), 0.0);
            const std::vector<int64_t> node_of = test::node_of_vertices(t);
            for (uint32_t v = 0; v < s.field.size(); ++v) {
                const int64_t node = node_of[v];
                const uint32_t b = node >= 0 ? d.node_branch[node] : d.arc_branch[t.vertex_arc[v]];
                count[b] += 1;
                sum[b] += s.field.f[v] - f_min;
            }
            for (uint32_t b = static_cast<uint32_t>(bs.size()); b-- > 0;) {
                if (b > 0) {
                    count[b] += 1;
                    sum[b] += s.field.f[t.node_vertex[bs[b].saddle_node]] - f_min;
                }
                for (const uint32_t c : d.children(b)) {
                    count[b] += count[c] - 1;
                    sum[b] += sum[c] - (s.field.f[t.node_vertex[bs[c].saddle_node]] - f_min);
                }
            }
            std::ostringstream err;
            for (uint32_t b = 0; b < bs.size(); ++b) {
                if (bs[b].measures[kVolume] != count[b])
                    err << "branch " << b << " volume " << bs[b].measures[kVolume] << ", summed "
                        << count[b] << "; ";
                if (std::fabs(bs[b].measures[kHypervolume] - sum[b]) > 1e-9 * (1.0 + std::fabs(sum[b])))
                    err << "branch " << b << " hypervolume " << bs[b].measures[kHypervolume]
                        << ", summed " << sum[b] << "; ";
            }
            return err.str();
        },
        true);
}

// What persistence guarantees: a child of the same kind as its parent (a
// maximum's branch hanging off a maximum's branch, or minimum off minimum) is
// never more persistent: the parent won at the child's saddle and reaches
// further from it.  (Across kinds it can be: see Crater in
// test_contour_tree_known.cpp.)
TEST(BranchDecompositionProperties, SameKindChildIsNeverMorePersistentThanItsParent)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const auto &bs = s.result->branches.branches;
            for (uint32_t b = 1; b < bs.size(); ++b) {
                const Branch &p = bs[bs[b].parent];
                if (p.kind != bs[b].kind)
                    continue;
                if (bs[b].importance > p.importance ||
                    bs[b].measures[kPersistence] > p.measures[kPersistence])
                    return "branch " + std::to_string(b) + " is more persistent than its parent";
            }
            return "";
        },
        true);
}

// ---- simplification ---------------------------------------------------------------------

// Nearest kept ancestor (or itself), by walking the parents.
uint32_t nearest_kept(const BranchDecomposition &d, const std::vector<char> &kept, uint32_t b)
{
    while (!kept[b])
        b = static_cast<uint32_t>(d.branches[b].parent);
    return b;
}

// Checks a cut against the set of branches it should keep: kept list, index
// maps, kept parents, and every voxel's label (regular voxels by their arc's
// branch, nodes by node_branch).
std::string check_cut(const Sample &s, const SimplificationCut &cut, const std::vector<char> &keep)
{
    const BranchDecomposition &d = s.result->branches;
    const ContourTree &t = s.result->tree;
    std::vector<uint32_t> want;
    for (uint32_t b = 0; b < keep.size(); ++b)
        if (keep[b])
            want.push_back(b);
    if (cut.kept != want)
        return "kept " + std::to_string(cut.kept.size()) + " branches, expected " + std::to_string(want.size());
    for (uint32_t b = 0; b < keep.size(); ++b) {
        const auto it = std::find(want.begin(), want.end(), b);
        const int32_t index = it == want.end() ? -1 : static_cast<int32_t>(it - want.begin());
        if (cut.kept_index[b] != index)
            return "kept_index of branch " + std::to_string(b);
        const uint32_t anc = nearest_kept(d, keep, b);
        if (cut.label_of[b] != static_cast<uint32_t>(cut.kept_index[anc]))
            return "label_of branch " + std::to_string(b) + " is not its nearest kept ancestor";
    }
    for (uint32_t i = 0; i < want.size(); ++i) {
        const int32_t p = d.branches[want[i]].parent;
        const int32_t expected = p < 0 ? -1 : cut.kept_index[nearest_kept(d, keep, static_cast<uint32_t>(p))];
        if (cut.kept_parent[i] != expected)
            return "kept_parent of kept branch " + std::to_string(want[i]);
    }
    const LabelMap labels = label_voxels(t, d, cut);
    if (labels.size() != s.field.size())
        return "label_voxels labels " + std::to_string(labels.size()) + " voxels";
    const std::vector<int64_t> node_of = test::node_of_vertices(t);
    for (uint32_t v = 0; v < labels.size(); ++v) {
        if (labels[v] >= cut.kept.size())
            return "voxel " + std::to_string(v) + " has label " + std::to_string(labels[v]);
        if (t.arc_count() == 0) {
            if (labels[v] != 0)
                return "a tree without arcs must label everything 0";
            continue;
        }
        const int64_t node = node_of[v];
        const uint32_t owner = node >= 0 ? d.node_branch[node] : d.arc_branch[t.vertex_arc[v]];
        if (labels[v] != static_cast<uint32_t>(cut.kept_index[nearest_kept(d, keep, owner)]))
            return "voxel " + std::to_string(v) + " is not labelled with the nearest kept ancestor of its branch";
    }
    return "";
}

// Importances of the non-root branches, most important first (ties: lower
// index first), as branch indices.
std::vector<uint32_t> by_importance(const BranchDecomposition &d)
{
    std::vector<uint32_t> idx;
    for (uint32_t b = 1; b < d.branches.size(); ++b)
        idx.push_back(b);
    std::stable_sort(idx.begin(), idx.end(),
                     [&](uint32_t a, uint32_t b) { return d.branches[a].importance > d.branches[b].importance; });
    return idx;
}

// cut_by_count(N) keeps the root and the N-1 most important others:
// min(N, branches) in all (the root even for N = 0).
TEST(SimplificationProperties, CutByCountKeepsTheMostImportant)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const BranchDecomposition &d = s.result->branches;
            const std::size_t total = d.branches.size();
            const std::vector<uint32_t> order = by_importance(d);
            for (std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{3}, total / 2,
                                      total - 1, total, total + 4}) {
                std::vector<char> keep(total, 0);
                keep[0] = 1;
                for (std::size_t i = 0; i + 1 < std::min(count, total); ++i)
                    keep[order[i]] = 1;
                const SimplificationCut cut = cut_by_count(d, count);
                if (cut.kept.size() != std::max<std::size_t>(1, std::min(count, total)))
                    return "cut_by_count(" + std::to_string(count) + ") kept " + std::to_string(cut.kept.size()) +
                           " of " + std::to_string(total);
                const std::string e = check_cut(s, cut, keep);
                if (!e.empty())
                    return "cut_by_count(" + std::to_string(count) + "): " + e;
            }
            return "";
        },
        true);
}

// cut_by_threshold(t) keeps the root and exactly the branches with
// importance > t.
TEST(SimplificationProperties, CutByThresholdKeepsImportanceAboveIt)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const BranchDecomposition &d = s.result->branches;
            std::vector<double> thresholds{-1.0, 0.0, 0.25, 0.5, 1.0, 2.0};
            for (uint32_t b = 1; b < d.branches.size(); ++b) {
                thresholds.push_back(d.branches[b].importance);
                thresholds.push_back(std::nextafter(d.branches[b].importance, -1.0));
            }
            for (const double th : thresholds) {
                std::vector<char> keep(d.branches.size(), 0);
                keep[0] = 1;
                for (uint32_t b = 1; b < d.branches.size(); ++b)
                    keep[b] = d.branches[b].importance > th;
                const std::string e = check_cut(s, cut_by_threshold(d, th), keep);
                if (!e.empty())
                    return "cut_by_threshold(" + std::to_string(th) + "): " + e;
            }
            return "";
        },
        true);
}

// Keeping the k most important branches is the threshold cut at the
// importance of the (k+1)-th whenever the two differ.
TEST(SimplificationProperties, CountAndThresholdCutsAgree)
{
    for_every_grid(
        [](const Sample &s) -> std::string {
            const BranchDecomposition &d = s.result->branches;
            const std::vector<uint32_t> order = by_importance(d);
            for (std::size_t k = 0; k <= order.size(); ++k) {
                const double th = k < order.size() ? d.branches[order[k]].importance : -1.0;
                if (k > 0 && k < order.size() && !(d.branches[order[k - 1]].importance > th))
                    continue; // a tie at the cut: the two cuts may legitimately differ
                if (cut_by_count(d, k + 1).kept != cut_by_threshold(d, th).kept)
                    return "cut_by_count(" + std::to_string(k + 1) + ") and cut_by_threshold(" +
                           std::to_string(th) + ") differ";
            }
            return "";
        },
        true);
}

} // namespace
} // namespace arbor
