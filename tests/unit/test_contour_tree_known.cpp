// Contour trees, branch decompositions and persistence pairs of tiny grids,
// worked out by hand.  Each test's comments give the reasoning: which vertices
// the Freudenthal triangulation connects, the join sweep (sublevel sets,
// upwards) and the split sweep (superlevel sets, downwards) in simulated order
// (value, then vertex id), and the elder rule.  Vertex id = x + nx*(y + ny*z).
//
// Neighbours (ALGORITHMS.md section 1): (+-1,0,0) (0,+-1,0) (0,0,+-1)
// +-(-1,1,0) +-(0,1,1) +-(-1,0,1) +-(-1,1,1).  In a 2D grid (nz = 1) a vertex
// (x, y) therefore has the six neighbours (x+-1, y), (x, y+-1), (x-1, y+1) and
// (x+1, y-1).
#include "topology_oracles.hpp"

#include "topology/branch_decomposition.hpp"
#include "topology/contour_tree.hpp"
#include "topology/persistence_pairs.hpp"
#include "topology/simplification.hpp"
#include "topology/topology_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace arbor {
namespace {

using namespace arbor::topology;
using test::Dims;
using test::PairKey;

// ---- helpers -------------------------------------------------------------------------

struct ExpectedNode {
    uint32_t vertex;
    NodeKind kind;
};

// Nodes in simulated order, with their kinds; node_up/node_down must agree
// with the arcs.
void expect_nodes(const ContourTree &tree, const std::vector<ExpectedNode> &expected)
{
    ASSERT_EQ(tree.node_count(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(tree.node_vertex[i], expected[i].vertex) << "node " << i;
        EXPECT_EQ(node_kind_name(tree.node_kind[i]), std::string(node_kind_name(expected[i].kind)))
            << "node " << i << " (vertex " << tree.node_vertex[i] << ")";
    }
    std::vector<int> up(tree.node_count(), 0), down(tree.node_count(), 0);
    for (std::size_t a = 0; a < tree.arc_count(); ++a) {
        ++up[tree.arc_lo[a]];
        ++down[tree.arc_hi[a]];
    }
    for (std::size_t i = 0; i < tree.node_count(); ++i) {
        EXPECT_EQ(tree.node_up[i], up[i]) << "node " << i;
        EXPECT_EQ(tree.node_down[i], down[i]) << "node " << i;
    }
}

// Arc index of the arc from vertex lo up to vertex hi, or -1.
int64_t arc_between(const ContourTree &tree, uint32_t lo, uint32_t hi)
{
    for (std::size_t a = 0; a < tree.arc_count(); ++a)
        if (tree.node_vertex[tree.arc_lo[a]] == lo && tree.node_vertex[tree.arc_hi[a]] == hi)
            return static_cast<int64_t>(a);
    return -1;
}

struct ExpectedArc {
    uint32_t lo, hi;                   // node vertices
    std::vector<uint32_t> interior;    // regular vertices on the arc
};

// The arcs (by their end vertices) and the augmentation: every regular
// vertex lies on the expected arc, every node carries one of its own arcs.
void expect_arcs(const ContourTree &tree, const std::vector<ExpectedArc> &expected)
{
    ASSERT_EQ(tree.arc_count(), expected.size());
    std::vector<int64_t> expected_arc(tree.vertex_arc.size(), -2); // -2: a node
    for (const ExpectedArc &e : expected) {
        const int64_t a = arc_between(tree, e.lo, e.hi);
        ASSERT_GE(a, 0) << "no arc from vertex " << e.lo << " up to vertex " << e.hi;
        for (uint32_t v : e.interior)
            expected_arc[v] = a;
    }
    const std::vector<int64_t> node_of = test::node_of_vertices(tree);
    for (uint32_t v = 0; v < tree.vertex_arc.size(); ++v) {
        const int64_t node = node_of[v];
        if (expected_arc[v] == -2) {
            ASSERT_GE(node, 0) << "vertex " << v << " should be a node";
            const uint32_t a = tree.vertex_arc[v];
            ASSERT_LT(a, tree.arc_count()) << "node vertex " << v;
            EXPECT_TRUE(tree.arc_lo[a] == node || tree.arc_hi[a] == node)
                << "node vertex " << v << " carries arc " << a << ", which does not touch it";
        } else {
            EXPECT_EQ(node, -1) << "vertex " << v << " should be regular";
            EXPECT_EQ(tree.vertex_arc[v], expected_arc[v]) << "vertex " << v;
        }
    }
}

std::set<PairKey> pair_set(const TopologyResult &r, const Volume &volume)
{
    const FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                          &volume.geometry()};
    std::set<PairKey> out;
    for (const PersistencePair &p : persistence_pairs(r.tree, r.branches, field))
        out.insert({p.type, p.birth, p.death});
    return out;
}

// Index of the branch with this saddle and extremum vertex, or -1.
int branch_of(const TopologyResult &r, uint32_t saddle_vertex, uint32_t extremum_vertex)
{
    const auto &bs = r.branches.branches;
    for (std::size_t b = 0; b < bs.size(); ++b)
        if (r.tree.node_vertex[bs[b].saddle_node] == saddle_vertex &&
            r.tree.node_vertex[bs[b].extremum_node] == extremum_vertex)
            return static_cast<int>(b);
    return -1;
}

struct ExpectedMeasures {
    double persistence, volume, hypervolume;
};

void expect_measures(const Branch &b, const ExpectedMeasures &m)
{
    EXPECT_DOUBLE_EQ(b.measures[kPersistence], m.persistence);
    EXPECT_DOUBLE_EQ(b.measures[kVolume], m.volume);
    EXPECT_DOUBLE_EQ(b.measures[kHypervolume], m.hypervolume);
}

TopologyResult topology_of(const Volume &volume, const ImportanceFn &importance = persistence_importance())
{
    return compute_topology(volume, importance);
}

// Volume, not persistence, decides which branch continues at a saddle.
ImportanceFn volume_importance()
{
    return [](const std::vector<BranchMeasures> &rows, std::vector<double> &out) {
        for (std::size_t i = 0; i < rows.size(); ++i)
            out[i] = rows[i].relative[kVolume];
    };
}

// Rows are listed top (largest y) first, as one reads a picture; returns the
// values in vertex-id order.
std::vector<double> rows_top_down(const std::vector<std::vector<double>> &rows)
{
    std::vector<double> values;
    for (auto it = rows.rbegin(); it != rows.rend(); ++it)
        values.insert(values.end(), it->begin(), it->end());
    return values;
}

// ---- (a) strips: the 1D merge structure --------------------------------------------------

// [3, 1, 4, 1, 5, 9, 2, 6] on 8x1x1: the only neighbours are x-1 and x+1.  In
// one dimension every point is its own contour, so the contour tree is the
// strip itself with its local extrema as nodes: an interior local minimum is
// born with two contours above it (a minimum with two arcs up), an interior
// local maximum has two arcs below, the two ends are leaves.
//   v0=3 end, above v1          -> maximum, one arc down
//   v1=1 (1 < 3, 1 < 4)         -> minimum, two arcs up; the global minimum
//                                  (v3 also has value 1, but the higher id)
//   v2=4 (4 > 1, 4 > 1)         -> maximum, two arcs down
//   v3=1 (1 < 4, 1 < 5)         -> minimum, two arcs up
//   v4=5 (1 < 5 < 9)            -> regular, on the arc v3 - v5
//   v5=9 (9 > 5, 9 > 2)         -> maximum, two arcs down; the global maximum
//   v6=2 (2 < 9, 2 < 6)         -> minimum, two arcs up
//   v7=6 end, above v6          -> maximum, one arc down
// Simulated order of the nodes: v1(1) v3(1) v6(2) v0(3) v2(4) v7(6) v5(9).
// Arcs are the monotone runs: v1-v0, v1-v2, v3-v2, v3-v5 (through v4),
// v6-v5, v6-v7: six arcs for seven nodes.
TEST(ContourTreeKnown, StripIsTheOneDimensionalMergeStructure)
{
    const std::vector<double> values{3, 1, 4, 1, 5, 9, 2, 6};
    // The same strip along x, y and z: the vertex ids are the same.
    for (const Dims dims : {Dims{8, 1, 1}, Dims{1, 8, 1}, Dims{1, 1, 8}}) {
        SCOPED_TRACE(testing::Message() << dims[0] << "x" << dims[1] << "x" << dims[2]);
        const Volume volume = test::make_volume(ARBOR_VOXEL_F32, dims, values);
        const ContourTree tree = test::staged_contour_tree(volume);
        expect_nodes(tree, {{1, NodeKind::Minimum},
                            {3, NodeKind::Minimum},
                            {6, NodeKind::Minimum},
                            {0, NodeKind::Maximum},
                            {2, NodeKind::Maximum},
                            {7, NodeKind::Maximum},
                            {5, NodeKind::Maximum}});
        EXPECT_EQ(std::vector<int>(tree.node_up.begin(), tree.node_up.end()),
                  (std::vector<int>{2, 2, 2, 0, 0, 0, 0}));
        EXPECT_EQ(std::vector<int>(tree.node_down.begin(), tree.node_down.end()),
                  (std::vector<int>{0, 0, 0, 1, 2, 1, 2}));
        expect_arcs(tree, {{1, 0, {}}, {1, 2, {}}, {3, 2, {}}, {3, 5, {4}}, {6, 5, {}}, {6, 7, {}}});
        EXPECT_EQ(tree.arc_count(), tree.node_count() - 1);
        // Every voxel's value lies within its arc's end values.
        for (uint32_t v = 0; v < 8; ++v) {
            const uint32_t a = tree.vertex_arc[v];
            EXPECT_LE(values[tree.node_vertex[tree.arc_lo[a]]], values[v]) << "vertex " << v;
            EXPECT_GE(values[tree.node_vertex[tree.arc_hi[a]]], values[v]) << "vertex " << v;
        }
    }
}

// The persistence pairs of the same strip, by the elder rule on the join and
// split trees (what TTK reports, and what branch_decomposition.hpp promises
// for persistence):
//  join (upwards): v1, v3, v6 start components; v2=4 merges {v1..} and {v3}:
//    v3 (the younger: same value, higher id) dies -> (0, v3, v2); v5=9
//    merges {v1..v5} and {v6, v7}: v6 dies -> (0, v6, v5).
//  split (downwards): v5, v7, v2, v0 start components; v6=2 merges {v5..}
//    and {v7}: v7 (6 < 9) dies -> (2, v6, v7); v3 merges {v2} and {v4, v5}:
//    v2 dies -> (2, v3, v2); v1 merges {v0} and the rest: v0 dies -> (2, v1, v0).
//  essential: (-1, v1, v5).
// The path from the global minimum v1 to the global maximum v5 runs
// v1 -> v2 -> v3 -> v5 and is not monotone, so no decomposition into monotone
// branches can pair v1 with v5; the pipeline must still not fail on a valid
// volume, and the pairs are defined regardless.
TEST(ContourTreeKnown, StripPersistencePairsFollowTheElderRule)
{
    const Volume volume = test::make_volume(ARBOR_VOXEL_F32, {8, 1, 1}, {3, 1, 4, 1, 5, 9, 2, 6});
    const std::set<PairKey> expected{{-1, 1, 5}, {0, 3, 2}, {0, 6, 5}, {2, 6, 7}, {2, 3, 2}, {2, 1, 0}};
    // The oracle agrees with the hand computation.
    const auto oracle = test::elder_rule_pairs(test::field_of(volume));
    EXPECT_EQ(std::set<PairKey>(oracle.begin(), oracle.end()), expected);
    try {
        const TopologyResult r = topology_of(volume);
        EXPECT_EQ(pair_set(r, volume), expected);
    } catch (const std::exception &e) {
        ADD_FAILURE() << "compute_topology failed on the 8x1x1 strip [3 1 4 1 5 9 2 6]: " << e.what();
    }
}

// The pairs file's lines, TTK's columns, for the strip [a, 4.25, 2.125, 6]:
// join: v0 and v2 start, v1 merges them, v2 dies -> (0, v2, v1); split: v3
// and v1 start, v2 merges them, v1 dies -> (2, v2, v1); the global pair
// (v0, v3).  Integer types print whole numbers (%.0f), the others nine
// significant digits (%.9g, as Python's '%.9g' prints the float 1/3).
TEST(ContourTreeKnown, PairsFileLinesAreTtksColumns)
{
    const auto lines_of = [](arbor_voxel_type type, const std::vector<double> &values) {
        const Volume volume = test::make_volume(type, {4, 1, 1}, values);
        const TopologyResult r = topology_of(volume);
        const FieldView field{volume.type(), volume.data(), static_cast<uint32_t>(volume.voxel_count()),
                              &volume.geometry()};
        std::ostringstream out;
        write_persistence_pairs(out, persistence_pairs(r.tree, r.branches, field), volume.geometry(), volume.type(),
                                "strip");
        std::vector<std::string> lines;
        std::istringstream in(out.str());
        for (std::string line; std::getline(in, line);)
            if (!line.empty() && line[0] != '#')
                lines.push_back(line);
        return lines;
    };
    EXPECT_EQ(lines_of(ARBOR_VOXEL_U8, {0, 4, 2, 6}),
              (std::vector<std::string>{"0 2 1 2 4 2 2 0 0 1 0 0", "2 2 1 2 4 2 2 0 0 1 0 0", "-1 0 3 0 6 6 0 0 0 3 0 0"}));
    EXPECT_EQ(lines_of(ARBOR_VOXEL_F32, {static_cast<double>(1.0f / 3.0f), 4.25, 2.125, 6}),
              (std::vector<std::string>{"0 2 1 2.125 4.25 2.125 2 0 0 1 0 0", "2 2 1 2.125 4.25 2.125 2 0 0 1 0 0",
                                        "-1 0 3 0.333333343 6 5.66666666 0 0 0 3 0 0"}));
}

// A strip whose global minimum and maximum are joined by a monotone path:
// [0, 5, 1, 3].  v0=0 end (minimum), v1=5 maximum with two arcs down (the
// global maximum), v2=1 minimum with two arcs up, v3=3 end (maximum).
//  join: v0 and v2 start; v1 merges them, v2 dies -> (0, v2, v1).
//  split: v1 and v3 start; v2 merges them, v3 dies -> (2, v2, v3).
// Branches: the root v0 -> v1; the maximum v3 hangs at v2; the minimum v2
// hangs at v1 (on the root).
TEST(ContourTreeKnown, StripWithMonotoneRootPath)
{
    const Volume volume = test::make_volume(ARBOR_VOXEL_U8, {4, 1, 1}, {0, 5, 1, 3});
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{0, NodeKind::Minimum}, {2, NodeKind::Minimum}, {3, NodeKind::Maximum},
                          {1, NodeKind::Maximum}});
    expect_arcs(r.tree, {{0, 1, {}}, {2, 1, {}}, {2, 3, {}}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, 1}, {0, 2, 1}, {2, 2, 3}}));
    ASSERT_EQ(r.branches.branches.size(), 3u);
    const int max_branch = branch_of(r, 2, 3), min_branch = branch_of(r, 1, 2);
    ASSERT_GE(max_branch, 0);
    ASSERT_GE(min_branch, 0);
    EXPECT_EQ(r.branches.branches[min_branch].kind, BranchKind::Minimum);
    EXPECT_EQ(r.branches.branches[max_branch].kind, BranchKind::Maximum);
    // Regions: the maximum v3 above v2 is {v2, v3}; the minimum v2 below v1
    // is everything beyond v1 on v2's side: {v1, v2, v3}.
    expect_measures(r.branches.branches[max_branch], {2, 2, 1 + 3});
    expect_measures(r.branches.branches[min_branch], {4, 3, 5 + 1 + 3});
}

// The smallest plane without ties where the path between the global
// extrema is not monotone.  3x2x1, values distinct:
//   y=1: v3=2  v4=3  v5=0        neighbours: rows, columns, and the
//   y=0: v0=5  v1=1  v2=4        diagonals v1-v3, v2-v4 (along (-1,1))
//   v0: {1,3}  v1: {0,2,3,4}  v2: {1,4,5}  v3: {0,1,4}  v4: {1,2,3,5}  v5: {2,4}
//  join (up): v5=0 starts; v1=1 starts (0, 2, 3, 4 are higher); v3=2
//    touches v1; v4=3 touches v3 (v1's component) and v5: join saddle, v1
//    dies -> (0, v1, v4); v2 and v0 touch one component each.
//  split (down): v0=5 starts; v2=4 starts (1, 4, 5 are lower); v4=3 touches
//    v2; v3=2 touches v4 (v2's) and v0: split saddle, v2 dies -> (2, v3, v2);
//    v1 and v5 touch one component each.
// Tree: v1 -- v3 (split saddle); v3 -- v0; v3 -- v4 (join saddle); v5 -- v4;
// v4 -- v2.  At h = 2.5 three arcs span h (v3-v0, v3-v4, v5-v4): the level set
// cuts off the corner v0, and the band {v4, v2} cuts off the corner v5 (two
// curves).  The global minimum v5 reaches the global maximum v0 only through
// v4 (3) and then v3 (2): down again, so no monotone root branch exists.
TEST(ContourTreeKnown, PlaneWhoseGlobalExtremaAreJoinedByANonMonotonePath)
{
    const Volume volume = test::make_volume(ARBOR_VOXEL_F32, {3, 2, 1}, {5, 1, 4, 2, 3, 0});
    const ContourTree tree = test::staged_contour_tree(volume);
    expect_nodes(tree, {{5, NodeKind::Minimum},
                        {1, NodeKind::Minimum},
                        {3, NodeKind::SplitSaddle},
                        {4, NodeKind::JoinSaddle},
                        {2, NodeKind::Maximum},
                        {0, NodeKind::Maximum}});
    expect_arcs(tree, {{1, 3, {}}, {3, 0, {}}, {3, 4, {}}, {5, 4, {}}, {4, 2, {}}});
    const std::set<PairKey> expected{{-1, 5, 0}, {0, 1, 4}, {2, 3, 2}};
    const auto oracle = test::elder_rule_pairs(test::field_of(volume));
    EXPECT_EQ(std::set<PairKey>(oracle.begin(), oracle.end()), expected);
    try {
        const TopologyResult r = topology_of(volume);
        EXPECT_EQ(pair_set(r, volume), expected);
    } catch (const std::exception &e) {
        ADD_FAILURE() << "compute_topology failed on the 3x2x1 plane [5 1 4 2 3 0]: " << e.what();
    }
}

// ---- (b) one cube -----------------------------------------------------------------------

// The 2x2x2 cube, ids x + 2y + 4z.  Its triangulation has the 12 cube edges,
// one diagonal on each face pair, +-(-1,1,0): 1-2, 5-6; +-(0,1,1): 0-6, 1-7;
// +-(-1,0,1): 1-4, 3-6, and the body diagonal +-(-1,1,1): 1-6.  So
//   0: {1,2,4,6}   1: {0,2,3,4,5,6,7}   2: {0,1,3,6}   3: {1,2,6,7}
//   4: {0,1,5,6}   5: {1,4,6,7}         6: {0,1,2,3,4,5,7}   7: {1,3,5,6}
// and the corners 0 and 7 are NOT neighbours (they would be with the (1,1,1)
// diagonal).
TEST(ContourTreeKnown, CubeNeighbours)
{
    const std::map<uint32_t, std::set<uint32_t>> expected{
        {0, {1, 2, 4, 6}}, {1, {0, 2, 3, 4, 5, 6, 7}}, {2, {0, 1, 3, 6}}, {3, {1, 2, 6, 7}},
        {4, {0, 1, 5, 6}}, {5, {1, 4, 6, 7}},          {6, {0, 1, 2, 3, 4, 5, 7}}, {7, {1, 3, 5, 6}}};
    const GridNeighbors grid(2, 2, 2);
    for (const auto &[v, neighbours] : expected) {
        std::set<uint32_t> got;
        grid.for_each(v, [&](int64_t w) { got.insert(static_cast<uint32_t>(w)); });
        EXPECT_EQ(got, neighbours) << "vertex " << v;
    }
}

// Two maxima at the non-adjacent corners 0 (10) and 7 (9), joined through the
// path 0 - 2 - 3 - 7:  v0=10 v1=0 v2=8 v3=7 v4=1 v5=2 v6=3 v7=9.
//  split (down): v0 starts; v7 starts (its neighbours 1,3,5,6 are all lower);
//    v2=8 touches v0; v3=7 touches v2 (component of v0) and v7 -> split
//    saddle, v7 (9 < 10) dies -> (2, v3, v7).  v6, v5, v4, v1 touch one
//    component each.
//  join (up): v1=0 starts; every later vertex touches v1's component.
// Tree: v1 (min) -- v4 v5 v6 -- v3 (split saddle); v3 -- v7; v3 -- v2 -- v0.
// Level set at 7.5: {v0, v2} and {v7} above, two contours = the arcs v3-v7
// and v3-v0.
TEST(ContourTreeKnown, CubeWithASplitSaddle)
{
    const Volume volume = test::make_volume(ARBOR_VOXEL_U8, {2, 2, 2}, {10, 0, 8, 7, 1, 2, 3, 9});
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{1, NodeKind::Minimum}, {3, NodeKind::SplitSaddle}, {7, NodeKind::Maximum},
                          {0, NodeKind::Maximum}});
    expect_arcs(r.tree, {{1, 3, {4, 5, 6}}, {3, 7, {}}, {3, 0, {2}}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 1, 0}, {2, 3, 7}}));

    ASSERT_EQ(r.branches.branches.size(), 2u);
    const Branch &root = r.branches.branches[0];
    EXPECT_EQ(root.kind, BranchKind::Root);
    // Root: all 8 voxels, hypervolume = sum of values (the minimum is 0).
    expect_measures(root, {10, 8, 10 + 0 + 8 + 7 + 1 + 2 + 3 + 9});
    const int b = branch_of(r, 3, 7);
    ASSERT_EQ(b, 1);
    EXPECT_EQ(r.branches.branches[b].parent, 0);
    EXPECT_EQ(r.branches.branches[b].depth, 1u);
    // The region above v3 on v7's side: {v3, v7}.
    expect_measures(r.branches.branches[b], {2, 2, 7 + 9});
}

// A degenerate saddle: three pairwise non-adjacent maxima 0 (10), 3 (9) and
// 5 (8) all touch vertex 6, which has 7 neighbours:
//   v0=10 v1=0 v2=1 v3=9 v4=2 v5=8 v6=5 v7=3.
//  split: v0, v3 (neighbours 1,2,6,7 lower), v5 (neighbours 1,4,6,7 lower)
//    start; v6 touches all three -> one split saddle with three arcs up;
//    v3 and v5 die there: (2, v6, v3), (2, v6, v5).
//  join: v1 starts; v2, v4, v7 (all next to v1) and the rest follow.
// Kept as one node of degree 4 (ALGORITHMS.md section 1).
TEST(ContourTreeKnown, CubeWithADegenerateSaddle)
{
    const Volume volume = test::make_volume(ARBOR_VOXEL_U8, {2, 2, 2}, {10, 0, 1, 9, 2, 8, 5, 3});
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{1, NodeKind::Minimum}, {6, NodeKind::SplitSaddle}, {5, NodeKind::Maximum},
                          {3, NodeKind::Maximum}, {0, NodeKind::Maximum}});
    EXPECT_EQ(r.tree.node_up[1], 3);
    expect_arcs(r.tree, {{1, 6, {2, 4, 7}}, {6, 5, {}}, {6, 3, {}}, {6, 0, {}}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 1, 0}, {2, 6, 3}, {2, 6, 5}}));
    const int b3 = branch_of(r, 6, 3), b5 = branch_of(r, 6, 5);
    ASSERT_GE(b3, 0);
    ASSERT_GE(b5, 0);
    EXPECT_EQ(r.branches.branches[b3].parent, 0);
    EXPECT_EQ(r.branches.branches[b5].parent, 0);
    expect_measures(r.branches.branches[b3], {4, 2, 5 + 9});
    expect_measures(r.branches.branches[b5], {3, 2, 5 + 8});
}

// ---- (c) two bumps and a saddle on a plateau ---------------------------------------------

// 7x5x1, background plateau 1, two bumps in row y = 3 (ids 21..27):
//   y=4: 1 1 1 1 1 1 1
//   y=3: 1 9 5 3 5 7 4      A=(1,3)=v22, (2,3)=v23, saddle (3,3)=v24,
//   y=2: 1 1 1 1 1 1 1      (4,3)=v25, B=(5,3)=v26, (6,3)=v27
//   y=1: 1 1 1 1 1 1 1
//   y=0: 1 1 1 1 1 1 1
// Simulation of simplicity orders the plateau by id, like a ramp.
//  join (up): the plateau first, v0 starts the only component: every other
//    plateau vertex has a lower-id plateau neighbour ((x-1,y), or (x,y-1)
//    for x = 0; (0,4) sits on (0,3)).  The bump vertices then each touch that
//    one component.  One minimum, v0.
//  split (down): A=9 starts, B=7 starts (its neighbours are lower); (4,3)=5
//    (id 25, above (2,3)=5 with id 23) touches B; (2,3) touches A; (6,3)=4
//    touches B; (3,3)=3 touches (2,3) and (4,3) -> split saddle, B (7 < 9)
//    dies: (2, v24, v26).  The plateau, downwards by id, starts at (6,4) =
//    v34, whose neighbour (6,3)=4 is already swept: no plateau maximum, and
//    every later plateau vertex touches the one component.
// Tree: v0 -- 28 plateau voxels -- v24; v24 -- v25 v27 -- v26; v24 -- v23 -- v22.
TEST(ContourTreeKnown, TwoBumpsAndASaddle)
{
    const std::vector<double> values = rows_top_down({{1, 1, 1, 1, 1, 1, 1},
                                                      {1, 9, 5, 3, 5, 7, 4},
                                                      {1, 1, 1, 1, 1, 1, 1},
                                                      {1, 1, 1, 1, 1, 1, 1},
                                                      {1, 1, 1, 1, 1, 1, 1}});
    const Volume volume = test::make_volume(ARBOR_VOXEL_I16, {7, 5, 1}, values);
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{0, NodeKind::Minimum}, {24, NodeKind::SplitSaddle}, {26, NodeKind::Maximum},
                          {22, NodeKind::Maximum}});
    std::vector<uint32_t> plateau;
    for (uint32_t v = 1; v < 35; ++v)
        if (v < 22 || v > 27)
            plateau.push_back(v);
    expect_arcs(r.tree, {{0, 24, plateau}, {24, 26, {25, 27}}, {24, 22, {23}}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, 22}, {2, 24, 26}}));

    ASSERT_EQ(r.branches.branches.size(), 2u);
    const Branch &root = r.branches.branches[0];
    EXPECT_EQ(r.tree.node_vertex[root.saddle_node], 0u);
    EXPECT_EQ(r.tree.node_vertex[root.extremum_node], 22u);
    // hypervolume is shifted by the global minimum, 1: only the bumps count.
    expect_measures(root, {8, 35, 8 + 4 + 2 + 4 + 6 + 3});
    const int b = branch_of(r, 24, 26);
    ASSERT_EQ(b, 1);
    const Branch &bump = r.branches.branches[b];
    EXPECT_EQ(bump.kind, BranchKind::Maximum);
    EXPECT_EQ(bump.parent, 0);
    // B's region: the saddle and the voxels above it on B's side, v24..v27
    // without v23: values 3, 5, 7, 4.
    expect_measures(bump, {4, 4, (3 - 1) + (5 - 1) + (7 - 1) + (4 - 1)});
    EXPECT_DOUBLE_EQ(bump.measures[kRelativeHypervolume], 0 + 2 + 4 + 1);
    EXPECT_DOUBLE_EQ(r.branches.relative(b, kPersistence), 4.0 / 8.0);
    EXPECT_DOUBLE_EQ(r.branches.relative(b, kVolume), 4.0 / 35.0);
    EXPECT_DOUBLE_EQ(bump.importance, 0.5);
    // The arcs: root owns v0-v24 and v24-v22, the bump v24-v26; the saddle
    // node belongs to the branch that continues through it.
    EXPECT_EQ(r.branches.arc_branch[arc_between(r.tree, 0, 24)], 0u);
    EXPECT_EQ(r.branches.arc_branch[arc_between(r.tree, 24, 22)], 0u);
    EXPECT_EQ(r.branches.arc_branch[arc_between(r.tree, 24, 26)], 1u);
    EXPECT_EQ(r.branches.node_branch[1], 0u);
    EXPECT_EQ(r.branches.node_branch[2], 1u);

    // Two kept branches: v25, v26, v27 carry the bump's label, all else the root's.
    const LabelMap labels = label_voxels(r.tree, r.branches, cut_by_count(r.branches, 2));
    for (uint32_t v = 0; v < 35; ++v)
        EXPECT_EQ(labels[v], (v == 25 || v == 26 || v == 27) ? 1u : 0u) << "vertex " << v;
    const LabelMap one = label_voxels(r.tree, r.branches, cut_by_count(r.branches, 1));
    EXPECT_EQ(one, LabelMap(35, 0u));
}

// Importance decides which branch continues at a saddle.  9x3x1, background
// 0 in rows 0-1 and at (0,2); three bumps along the top row (ids 18..26):
//   y=2: 0 8 3 6 6 6 2 9 5     A=(1,2)=v19 (8), s1=(2,2)=v20 (3),
//   y=1: 0 0 0 0 0 0 0 0 0     (3,2)=v21, (4,2)=v22, B=(5,2)=v23 (6, the
//   y=0: 0 0 0 0 0 0 0 0 0     highest id of the three 6s), s2=(6,2)=v24 (2),
//                              C=(7,2)=v25 (9), (8,2)=v26 (5)
//  split (down): C, A, B start; (4,2), (3,2) join B; (8,2) joins C; s1
//    merges A and B; s2 merges {A,B} and C.  The background's highest id,
//    (0,2)=v18, touches A; (8,1) touches (8,2): no background maximum.
//  join (up): the background is one component from v0; every bump vertex
//    touches it (row 1 lies under row 2).
// Tree: v0 -- v24; v24 -- v26 -- v25; v24 -- v20; v20 -- v19; v20 -- v21 v22 -- v23.
// Persistence (elder rule): at s1, B (6-3 = 3) ends, A (8-3 = 5) goes on; at
// s2, A ends (C is the global maximum).  Pairs (2, v20, v23), (2, v24, v19).
// Volume: at s1, A's side {s1, A} has 2 voxels, B's {s1, v21, v22, B} 4:
// B goes on and A ends at s1.  Pairs (2, v20, v19), (2, v24, v23).
TEST(ContourTreeKnown, ImportanceDecidesWhichBranchContinues)
{
    const std::vector<double> values = rows_top_down(
        {{0, 8, 3, 6, 6, 6, 2, 9, 5}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}});
    const Volume volume = test::make_volume(ARBOR_VOXEL_U8, {9, 3, 1}, values);
    std::vector<uint32_t> background;
    for (uint32_t v = 1; v <= 18; ++v)
        background.push_back(v);

    const TopologyResult p = topology_of(volume);
    expect_nodes(p.tree, {{0, NodeKind::Minimum}, {24, NodeKind::SplitSaddle}, {20, NodeKind::SplitSaddle},
                          {23, NodeKind::Maximum}, {19, NodeKind::Maximum}, {25, NodeKind::Maximum}});
    expect_arcs(p.tree, {{0, 24, background}, {24, 25, {26}}, {24, 20, {}}, {20, 19, {}}, {20, 23, {21, 22}}});
    EXPECT_EQ(pair_set(p, volume), (std::set<PairKey>{{-1, 0, 25}, {2, 24, 19}, {2, 20, 23}}));
    expect_measures(p.branches.branches[0], {9, 27, 8 + 3 + 6 + 6 + 6 + 2 + 9 + 5});
    const int pa = branch_of(p, 24, 19), pb = branch_of(p, 20, 23);
    ASSERT_GE(pa, 0);
    ASSERT_GE(pb, 0);
    EXPECT_EQ(p.branches.branches[pa].parent, 0);
    EXPECT_EQ(p.branches.branches[pb].parent, pa);
    EXPECT_EQ(p.branches.branches[pb].depth, 2u);
    // A's branch encloses everything above s2 on its side: s2, s1, A, B's three.
    expect_measures(p.branches.branches[pa], {6, 6, 2 + 3 + 8 + 6 + 6 + 6});
    expect_measures(p.branches.branches[pb], {3, 4, 3 + 6 + 6 + 6});

    const TopologyResult v = topology_of(volume, volume_importance());
    EXPECT_EQ(pair_set(v, volume), (std::set<PairKey>{{-1, 0, 25}, {2, 24, 23}, {2, 20, 19}}));
    const int va = branch_of(v, 20, 19), vb = branch_of(v, 24, 23);
    ASSERT_GE(va, 0);
    ASSERT_GE(vb, 0);
    EXPECT_EQ(v.branches.branches[vb].parent, 0);
    EXPECT_EQ(v.branches.branches[va].parent, vb);
    expect_measures(v.branches.branches[vb], {4, 6, 2 + 3 + 8 + 6 + 6 + 6});
    expect_measures(v.branches.branches[va], {5, 2, 3 + 8});
    EXPECT_DOUBLE_EQ(v.branches.branches[va].importance, 2.0 / 27.0);
    EXPECT_DOUBLE_EQ(v.branches.branches[vb].importance, 6.0 / 27.0);
}

// ---- (d) constant fields, (e) one voxel ------------------------------------------------

// All values equal: simulation of simplicity orders the vertices by id, which
// is the linear function x + nx*y + nx*ny*z on the grid.  A linear function
// on a convex domain has one minimum (vertex 0), one maximum (vertex n-1) and
// every other vertex regular: one arc, one (root) branch of persistence 0.
TEST(ContourTreeKnown, ConstantFieldIsARampById)
{
    struct Case {
        arbor_voxel_type type;
        Dims dims;
        double value;
    };
    for (const Case &c : {Case{ARBOR_VOXEL_U8, {4, 1, 1}, 7}, Case{ARBOR_VOXEL_U8, {1, 1, 5}, 0},
                          Case{ARBOR_VOXEL_I16, {3, 2, 2}, -3}, Case{ARBOR_VOXEL_F32, {2, 3, 4}, 0.25},
                          Case{ARBOR_VOXEL_F32, {1, 4, 3}, -1.5}, Case{ARBOR_VOXEL_I16, {5, 5, 5}, 100}}) {
        SCOPED_TRACE(testing::Message() << c.dims[0] << "x" << c.dims[1] << "x" << c.dims[2] << " of "
                                        << c.value);
        const uint32_t n = static_cast<uint32_t>(c.dims[0] * c.dims[1] * c.dims[2]);
        const Volume volume = test::make_volume(c.type, c.dims, std::vector<double>(n, c.value));
        const TopologyResult r = topology_of(volume);
        expect_nodes(r.tree, {{0, NodeKind::Minimum}, {n - 1, NodeKind::Maximum}});
        std::vector<uint32_t> interior;
        for (uint32_t v = 1; v + 1 < n; ++v)
            interior.push_back(v);
        expect_arcs(r.tree, {{0, n - 1, interior}});
        ASSERT_EQ(r.branches.branches.size(), 1u);
        const Branch &root = r.branches.branches[0];
        EXPECT_EQ(root.kind, BranchKind::Root);
        EXPECT_EQ(root.parent, -1);
        EXPECT_TRUE(std::isinf(root.importance));
        expect_measures(root, {0, double(n), 0});
        EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, n - 1}}));
    }
}

TEST(ContourTreeKnown, SingleVoxelIsOneLoneNode)
{
    const Volume volume = test::make_volume(ARBOR_VOXEL_F32, {1, 1, 1}, {42.5});
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{0, NodeKind::Lone}});
    EXPECT_EQ(r.tree.arc_count(), 0u);
    EXPECT_EQ(r.tree.vertex_arc[0], kNoArc);
    ASSERT_EQ(r.branches.branches.size(), 1u);
    const Branch &root = r.branches.branches[0];
    EXPECT_EQ(root.kind, BranchKind::Root);
    EXPECT_EQ(root.extremum_node, 0u);
    EXPECT_EQ(root.saddle_node, 0u);
    expect_measures(root, {0, 1, 0});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, 0}}));
    EXPECT_EQ(label_voxels(r.tree, r.branches, cut_by_count(r.branches, 3)), LabelMap{0u});
}

// ---- (f) a pit: a minimum inside a ring ------------------------------------------------

// 5x5x1: the global minimum at the corner (0,0)=0; the border rises along the
// cycle (0,0) -> (4,0) -> (4,4) -> (0,4) -> (0,1) through 10, 11, ..., 24;
// a ring of 30..37 around the pit (2,2)=1:
//   y=4: 21 20 19 18 17
//   y=3: 22 35 36 37 16        ring: (1,1)=30 (2,1)=31 (3,1)=32 (1,2)=33
//   y=2: 23 33  1 34 15              (3,2)=34 (1,3)=35 (2,3)=36 (3,3)=37
//   y=1: 24 30 31 32 14
//   y=0:  0 10 11 12 13
// The pit's neighbours are (1,2) (3,2) (2,1) (2,3) (1,3) (3,1): all ring.
//  join (up): v0 starts; the pit v12 starts (all its neighbours are higher);
//    the border joins v0 one by one (each border vertex touches the previous
//    one; (0,1)=24 closes a loop, not a merge).  (1,1)=30 is no pit
//    neighbour and touches only the border.  (2,1)=31 = v7 touches the pit
//    and the border ((2,0), (3,0)): join saddle, the pit dies:
//    (0, v12, v7), persistence 30.
//  split (down): (3,3)=37 = v18 starts; every other ring vertex touches an
//    earlier one; each border vertex touches the ring or a higher border
//    vertex: one maximum.
// Tree: v0 -- border, (1,1) -- v7; v12 -- v7; v7 -- (3,1) (1,2) (3,2) (1,3) (2,3) -- v18.
TEST(ContourTreeKnown, PitInAPlane)
{
    const std::vector<double> values = rows_top_down({{21, 20, 19, 18, 17},
                                                      {22, 35, 36, 37, 16},
                                                      {23, 33, 1, 34, 15},
                                                      {24, 30, 31, 32, 14},
                                                      {0, 10, 11, 12, 13}});
    const Volume volume = test::make_volume(ARBOR_VOXEL_U8, {5, 5, 1}, values);
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{0, NodeKind::Minimum}, {12, NodeKind::Minimum}, {7, NodeKind::JoinSaddle},
                          {18, NodeKind::Maximum}});
    expect_arcs(r.tree, {{0, 7, {1, 2, 3, 4, 5, 9, 10, 14, 15, 19, 20, 21, 22, 23, 24, 6}},
                         {12, 7, {}},
                         {7, 18, {8, 11, 13, 16, 17}}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, 18}, {0, 12, 7}}));
    const int pit = branch_of(r, 7, 12);
    ASSERT_EQ(pit, 1);
    EXPECT_EQ(r.branches.branches[pit].kind, BranchKind::Minimum);
    // The pit's region: the pit and its saddle.
    expect_measures(r.branches.branches[pit], {30, 2, 1 + 31});
    EXPECT_DOUBLE_EQ(r.branches.branches[pit].measures[kRelativeHypervolume], 30);
    expect_measures(r.branches.branches[0], {37, 25, 255 + 268 + 1});
}

// The same pit at the bottom of a thin 3D grid, 5x5x2, under a lid of 40s
// (ids 25..49).  The pit's upper neighbours (2,2,1) (2,3,1) (1,2,1) (1,3,1)
// are lid voxels, so it stays a minimum and (2,1,0) = v7 is still the first
// vertex touching both the pit and the border.  Downwards the lid is one
// plateau, swept by id from (4,4,1) = v49, and every voxel of layer 0 has the
// lid above it: (3,3,0) is no longer a maximum, v49 is the only one.
TEST(ContourTreeKnown, PitUnderALid)
{
    std::vector<double> values = rows_top_down({{21, 20, 19, 18, 17},
                                                {22, 35, 36, 37, 16},
                                                {23, 33, 1, 34, 15},
                                                {24, 30, 31, 32, 14},
                                                {0, 10, 11, 12, 13}});
    values.resize(50, 40);
    const Volume volume = test::make_volume(ARBOR_VOXEL_I16, {5, 5, 2}, values);
    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{0, NodeKind::Minimum}, {12, NodeKind::Minimum}, {7, NodeKind::JoinSaddle},
                          {49, NodeKind::Maximum}});
    std::vector<uint32_t> upper{8, 11, 13, 16, 17, 18};
    for (uint32_t v = 25; v < 49; ++v)
        upper.push_back(v);
    expect_arcs(r.tree, {{0, 7, {1, 2, 3, 4, 5, 9, 10, 14, 15, 19, 20, 21, 22, 23, 24, 6}},
                         {12, 7, {}},
                         {7, 49, upper}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, 49}, {0, 12, 7}}));
    const int pit = branch_of(r, 7, 12);
    ASSERT_GE(pit, 0);
    expect_measures(r.branches.branches[pit], {30, 2, 1 + 31});
}

// ---- a pit inside a peak: a child more persistent than its parent --------------------------

// 9x5x1 (u8), background 0.  A crater: a rim around the pit (2,2)=1, its
// highest point e=(3,3)=9, its lowest s=(2,1)=6.  A ridge joins the crater to
// the global maximum G=(8,4)=10 over the pass p=(4,3)=5:
//   y=4: 0 0 0 0 0 0 0 0 10
//   y=3: 0 7 8 9 5 7 8 8 9        ids: s = v11, pit = v20, e = v30,
//   y=2: 0 7 1 8 0 0 0 0 0             p = v31, G = v44
//   y=1: 0 7 6 7 0 0 0 0 0
//   y=0: 0 0 0 0 0 0 0 0 0
//  split (down): G starts, (8,3) joins it; e starts (its neighbours are
//    lower); the rim joins e around the ring, the ridge joins G; p touches e
//    (via (3,3)) and G (via (5,3)): split saddle, e (9 < 10) dies:
//    (2, v31, v30), persistence 4.  The background's highest id, (7,4),
//    touches G.
//  join (up): the background is one component from v0; the pit starts one;
//    p=5 touches only background; s=6 touches the pit and the background
//    ((2,0), (3,0)): join saddle, the pit dies: (0, v20, v11), persistence 5.
// Tree: v0 -- background -- p; p -- (5,3) (6,3) (7,3) (8,3) -- G; p -- s;
//   pit -- s; s -- rim -- e.
// Branches: root v0 -> p -> G; e's branch p -> s -> e; the pit's branch hangs
// at s, which lies on e's branch: the pit (persistence 5) is a child of e's
// branch (persistence 4).  Persistence does not decrease from parent to child
// across kinds; simplification must still label by nearest kept ancestor.
class Crater : public testing::Test {
protected:
    static std::vector<double> values()
    {
        return rows_top_down({{0, 0, 0, 0, 0, 0, 0, 0, 10},
                              {0, 7, 8, 9, 5, 7, 8, 8, 9},
                              {0, 7, 1, 8, 0, 0, 0, 0, 0},
                              {0, 7, 6, 7, 0, 0, 0, 0, 0},
                              {0, 0, 0, 0, 0, 0, 0, 0, 0}});
    }
    Volume volume = test::make_volume(ARBOR_VOXEL_U8, {9, 5, 1}, values());
    TopologyResult r = topology_of(volume);
};

TEST_F(Crater, TreeAndPairs)
{
    expect_nodes(r.tree, {{0, NodeKind::Minimum}, {20, NodeKind::Minimum}, {31, NodeKind::SplitSaddle},
                          {11, NodeKind::JoinSaddle}, {30, NodeKind::Maximum}, {44, NodeKind::Maximum}});
    std::vector<uint32_t> background;
    const std::set<uint32_t> structure{10, 11, 12, 19, 20, 21, 28, 29, 30, 31, 32, 33, 34, 35, 44};
    for (uint32_t v = 1; v < 45; ++v)
        if (!structure.count(v))
            background.push_back(v);
    ASSERT_EQ(background.size(), 29u);
    expect_arcs(r.tree, {{0, 31, background},
                         {31, 44, {32, 33, 34, 35}},
                         {31, 11, {}},
                         {20, 11, {}},
                         {11, 30, {10, 12, 19, 21, 28, 29}}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, 44}, {2, 31, 30}, {0, 20, 11}}));
}

TEST_F(Crater, PitIsAChildOfThePeakAndMorePersistent)
{
    ASSERT_EQ(r.branches.branches.size(), 3u);
    const int peak = branch_of(r, 31, 30), pit = branch_of(r, 11, 20);
    ASSERT_EQ(peak, 1);
    ASSERT_EQ(pit, 2);
    const Branch &pk = r.branches.branches[peak];
    const Branch &pt = r.branches.branches[pit];
    EXPECT_EQ(pk.parent, 0);
    EXPECT_EQ(pt.parent, peak);
    EXPECT_EQ(pt.depth, 2u);
    EXPECT_DOUBLE_EQ(pk.importance, 0.4);
    EXPECT_DOUBLE_EQ(pt.importance, 0.5);
    // The peak's region: p, the rim, and the pit it encloses (10 voxels).
    expect_measures(pk, {4, 10, 5 + (7 + 6 + 7 + 7 + 8 + 7 + 8 + 9) + 1});
    expect_measures(pt, {5, 2, 6 + 1});
    expect_measures(r.branches.branches[0], {10, 45, 59 + 1 + (5 + 7 + 8 + 8 + 9) + 10});
}

// Relative hypervolume is documented (branch_decomposition.hpp, the SDK's
// ARBOR_MEASURE_RELATIVE_HYPERVOLUME) as the volume between the function and
// the saddle level: the sum over the region of f - f(saddle) for a peak.  The
// peak's region holds the pit (1 < 5), which counts against it: 0 (p) + rim
// (2+1+2+2+3+2+3+4 = 19) + (1 - 5) = 15, where the sum of |f - f(saddle)|
// would be 23.  The pit's region lies below its saddle: 5 either way.
TEST_F(Crater, RelativeHypervolumeIsTheVolumeBetweenFunctionAndSaddleLevel)
{
    const int peak = branch_of(r, 31, 30), pit = branch_of(r, 11, 20);
    ASSERT_GE(peak, 0);
    ASSERT_GE(pit, 0);
    EXPECT_DOUBLE_EQ(r.branches.branches[peak].measures[kRelativeHypervolume], 15);
    EXPECT_DOUBLE_EQ(r.branches.branches[pit].measures[kRelativeHypervolume], 5);
}

// Threshold 0.45 keeps the root and the pit (0.5) but not the peak (0.4): the
// pit hangs off its nearest kept ancestor, the root, and the peak's voxels go
// to the root.
TEST_F(Crater, CutKeepsAChildWhoseParentIsRemoved)
{
    const SimplificationCut cut = cut_by_threshold(r.branches, 0.45);
    EXPECT_EQ(cut.kept, (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(cut.kept_index, (std::vector<int32_t>{0, -1, 1}));
    EXPECT_EQ(cut.label_of, (std::vector<uint32_t>{0, 0, 1}));
    EXPECT_EQ(cut.kept_parent, (std::vector<int32_t>{-1, 0}));
    const LabelMap labels = label_voxels(r.tree, r.branches, cut);
    for (uint32_t v = 0; v < 45; ++v)
        EXPECT_EQ(labels[v], v == 20 ? 1u : 0u) << "vertex " << v;
    // The two most important branches are the same two.
    EXPECT_EQ(cut_by_count(r.branches, 2).kept, cut.kept);
    // Keeping everything: the rim and the saddle s (on the peak's branch,
    // which continues through it) are the peak's; the pit is the pit's.
    const LabelMap all = label_voxels(r.tree, r.branches, cut_by_threshold(r.branches, 0.0));
    for (uint32_t v : {10u, 11u, 12u, 19u, 21u, 28u, 29u, 30u})
        EXPECT_EQ(all[v], 1u) << "vertex " << v;
    EXPECT_EQ(all[20], 2u);
    EXPECT_EQ(all[31], 0u);
}

// ---- the thesis' hypervolume example (section 4.4) ----------------------------------------

// Two branches b1, b2 with p = 98 and v = 50: b1's region holds 49 voxels of
// 100 and one of 2, b2's 49 of 2 and one of 100; hv1 = 4902, hv2 = 198 (the
// thesis integrates f; our hypervolume subtracts the global minimum, 0 here).
//
// A 17x10x2 grid: layer z = 0 is all 0 (it carries the global minimum v0 and
// connects the background, so the upward sweep has one component and no
// saddles); the structure lies in layer z = 1 (ids 170 + x + 17y):
//   a ridge  y = 1, x = 1..15, value 150, with G = (15,1) = 200
//   s1 = (4,2) = 2,  s2 = (12,2) = 2   (touch the ridge below, a box above)
//   b1 box  x = 1..7,  y = 3..9: 49 voxels of 100
//   b2 box  x = 9..15, y = 3..9: 48 voxels of 2 and (15,9) = 100
// everything else 0.  The boxes touch only background, their saddle, and
// (b2) nothing of the ridge.  The region of a branch is its saddle plus
// everything beyond the saddle on its side (branch_decomposition.hpp).  For b2,
// simulation of simplicity does the work: its 48 plateau voxels have value 2
// like s2, but higher ids (>= 170 + 9 + 51), so they lie above s2 and inside
// b2's region, while s2 (id 170 + 46) is the lowest of them and merges b2's
// component with the ridge.  Downwards, b2's plateau is swept from its
// highest id, (15,9) being the maximum itself, and every other plateau voxel
// has a higher-id neighbour in the box: no extra maxima.  The background's
// highest id, (16,9,1), touches b2's maximum.
//  split: G, the ridge; b2's maximum (100, id 338) and b1's top corner (100,
//    id 330) start; s2 merges b2 with the ridge (b2 dies, 100 < 200), s1
//    merges b1 with it (b1 dies).
//   b1: p = 100 - 2 = 98, v = 1 + 49 = 50, hv = 2 + 49*100 = 4902
//   b2: p = 100 - 2 = 98, v = 1 + 48 + 1 = 50, hv = 2 + 48*2 + 100 = 198
TEST(ThesisExample, EqualPersistenceAndVolumeDifferentHypervolume)
{
    const int64_t nx = 17, ny = 10;
    std::vector<double> values(static_cast<std::size_t>(nx * ny * 2), 0.0);
    const auto at = [&](int64_t x, int64_t y) -> double & { return values[x + nx * (y + ny * 1)]; };
    for (int64_t x = 1; x <= 15; ++x)
        at(x, 1) = 150;
    at(15, 1) = 200;
    at(4, 2) = 2;
    at(12, 2) = 2;
    for (int64_t y = 3; y <= 9; ++y) {
        for (int64_t x = 1; x <= 7; ++x)
            at(x, y) = 100;
        for (int64_t x = 9; x <= 15; ++x)
            at(x, y) = 2;
    }
    at(15, 9) = 100;
    const Volume volume = test::make_volume(ARBOR_VOXEL_U8, {nx, ny, 2}, values);
    const auto id = [&](int64_t x, int64_t y) { return static_cast<uint32_t>(x + nx * (y + ny)); };
    const uint32_t g = id(15, 1), s1 = id(4, 2), s2 = id(12, 2), m1 = id(7, 9), m2 = id(15, 9);

    const TopologyResult r = topology_of(volume);
    expect_nodes(r.tree, {{0, NodeKind::Minimum}, {s1, NodeKind::SplitSaddle}, {s2, NodeKind::SplitSaddle},
                          {m1, NodeKind::Maximum}, {m2, NodeKind::Maximum}, {g, NodeKind::Maximum}});
    EXPECT_EQ(pair_set(r, volume), (std::set<PairKey>{{-1, 0, g}, {2, s1, m1}, {2, s2, m2}}));
    const int b1 = branch_of(r, s1, m1), b2 = branch_of(r, s2, m2);
    ASSERT_GE(b1, 0);
    ASSERT_GE(b2, 0);
    expect_measures(r.branches.branches[b1], {98, 50, 4902});
    expect_measures(r.branches.branches[b2], {98, 50, 198});
    // Carr's relative hypervolume, sum of |f - f(saddle)|: 49*98 and 98.
    EXPECT_DOUBLE_EQ(r.branches.branches[b1].measures[kRelativeHypervolume], 4802);
    EXPECT_DOUBLE_EQ(r.branches.branches[b2].measures[kRelativeHypervolume], 98);
    // The root: every voxel, hypervolume the sum of all values.
    expect_measures(r.branches.branches[0], {200, 340, 4900 + 196 + 2 + 2 + 14 * 150 + 200});
    // Equal p and v, different hv: the relative measures tell them apart only
    // through hypervolume.
    EXPECT_EQ(r.branches.relative(b1, kPersistence),
              r.branches.relative(b2, kPersistence));
    EXPECT_EQ(r.branches.relative(b1, kVolume),
              r.branches.relative(b2, kVolume));
    EXPECT_GT(r.branches.relative(b1, kHypervolume),
              r.branches.relative(b2, kHypervolume));
}

} // namespace
} // namespace arbor
