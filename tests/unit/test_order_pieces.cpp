// The vertex order streamed in pieces (order_pieces.hpp), the in-place
// segmentation (UninitializedBuffer::shrink_to) and the choice of memory
// plan: the oracle is the whole order of sort_vertices, and the contour tree
// computed with the whole order.
#include "topology_oracles.hpp"

#include "topology/order_pieces.hpp"
#include "topology/topology_pipeline.hpp"
#include "topology/vertex_order.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace arbor {
namespace {

using namespace topology;

Volume random_integer_volume(arbor_voxel_type type, const test::Dims &dims, int lo, int hi, uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> u(lo, hi);
    std::vector<double> values(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
    for (double &v : values)
        v = u(rng);
    return test::make_volume(type, dims, values, {1.0, 1.0, 1.0});
}

std::vector<uint32_t> walked(const OrderPieces &order, bool downwards, std::vector<uint32_t> *firsts = nullptr)
{
    std::vector<uint32_t> out;
    order.walk(downwards, [&](const OrderPiece &piece, uint32_t first) {
        EXPECT_EQ(first, out.size());
        if (firsts)
            firsts->push_back(first);
        // The look-ahead past the piece is the next piece's start.
        const uint32_t ahead = std::min<uint32_t>(OrderPieces::kLookahead, order.size() - first - piece.count);
        for (uint32_t i = 0; i < piece.count + ahead; ++i)
            out.push_back(piece[i]);
        out.resize(first + piece.count);
    });
    return out;
}

TEST(OrderPieces, RangesAndWalksEqualTheWholeOrderForEveryTypeAndPieceSize)
{
    struct Case {
        arbor_voxel_type type;
        int lo, hi;
    };
    // Plateaus (ties by vertex id), wide ranges, and the extremes of each type.
    const Case cases[] = {{ARBOR_VOXEL_U8, 0, 3},        {ARBOR_VOXEL_U8, 0, 255},     {ARBOR_VOXEL_I8, -128, 127},
                          {ARBOR_VOXEL_U16, 0, 65535},   {ARBOR_VOXEL_U16, 1000, 1003}, {ARBOR_VOXEL_I16, -32768, 32767},
                          {ARBOR_VOXEL_I16, -1024, 3071}};
    uint64_t seed = 1;
    for (const Case &c : cases) {
        const Volume volume = random_integer_volume(c.type, {13, 7, 5}, c.lo, c.hi, seed++);
        const uint32_t n = static_cast<uint32_t>(volume.voxel_count());
        const UninitializedBuffer<uint32_t> whole = sort_vertices(volume.type(), volume.data(), n);
        const std::vector<uint32_t> up(whole.data(), whole.data() + n), down(up.rbegin(), up.rend());
        const std::vector<uint32_t> starts = count_value_starts(volume.type(), volume.data(), n);
        for (uint32_t lo = 0; lo <= n; lo += 37)
            for (uint32_t hi = lo; hi <= n; hi += 53) {
                std::vector<uint32_t> got(hi - lo, ~0u), want(up.begin() + lo, up.begin() + hi);
                fill_order_range(volume.type(), volume.data(), n, starts, lo, hi, false, got.data());
                ASSERT_EQ(got, want) << arbor_voxel_type_name(c.type) << " ranks " << lo << ".." << hi;
                fill_order_range(volume.type(), volume.data(), n, starts, lo, hi, true, got.data());
                std::reverse(want.begin(), want.end());
                ASSERT_EQ(got, want) << arbor_voxel_type_name(c.type) << " ranks " << lo << ".." << hi << " reversed";
            }
        for (const uint32_t piece : {1u, 2u, 63u, 64u, 65u, 100u, n - 1, n, n + 5}) {
            const OrderPieces streamed(volume.type(), volume.data(), n, piece);
            std::vector<uint32_t> firsts;
            EXPECT_EQ(walked(streamed, false, &firsts), up) << arbor_voxel_type_name(c.type) << " piece " << piece;
            EXPECT_EQ(firsts.size(), (n + piece - 1) / piece);
            EXPECT_EQ(walked(streamed, true), down) << arbor_voxel_type_name(c.type) << " piece " << piece;
        }
        const OrderPieces held(sort_vertices(volume.type(), volume.data(), n));
        EXPECT_EQ(walked(held, false), up);
        EXPECT_EQ(walked(held, true), down);
    }
}

TEST(OrderPieces, StreamingIsRefusedForWideTypesAndForeignCounts)
{
    const Volume f = test::make_volume(ARBOR_VOXEL_F32, {2, 2, 2}, {0, 1, 2, 3, 4, 5, 6, 7}, {1, 1, 1});
    EXPECT_THROW(OrderPieces(f.type(), f.data(), 8, 2), std::invalid_argument);
    const Volume u8 = test::make_volume(ARBOR_VOXEL_U8, {2, 2, 2}, {0, 1, 2, 3, 4, 5, 6, 7}, {1, 1, 1});
    const Volume u16 = test::make_volume(ARBOR_VOXEL_U16, {2, 2, 2}, {0, 1, 2, 3, 4, 5, 6, 7}, {1, 1, 1});
    const std::vector<uint32_t> starts = count_value_starts(u8.type(), u8.data(), 8);
    uint32_t out[8];
    EXPECT_THROW(fill_order_range(u16.type(), u16.data(), 8, starts, 0, 8, false, out), std::invalid_argument);
    EXPECT_THROW(fill_order_range(u8.type(), u8.data(), 8, starts, 4, 9, false, out), std::invalid_argument);
}

// A CT-like volume big enough for the sweeps' look-ahead to cross many
// pieces: the streamed tree is the whole order's, vertex for vertex.
TEST(OrderPieces, StreamedTreeEqualsTheWholeOrdersTree)
{
    const Volume volume = random_integer_volume(ARBOR_VOXEL_I16, {41, 29, 23}, -1024, -1000, 17);
    const ContourTree whole = test::staged_contour_tree(volume);
    for (const uint32_t piece : {7u, 1000u, 9000u}) {
        const ContourTree streamed = test::staged_contour_tree(volume, piece);
        EXPECT_EQ(streamed.node_vertex, whole.node_vertex) << "piece " << piece;
        EXPECT_EQ(streamed.arc_lo, whole.arc_lo) << "piece " << piece;
        EXPECT_EQ(streamed.arc_hi, whole.arc_hi) << "piece " << piece;
        ASSERT_EQ(streamed.vertex_arc.size(), whole.vertex_arc.size());
        for (std::size_t v = 0; v < whole.vertex_arc.size(); ++v)
            ASSERT_EQ(streamed.vertex_arc[v], whole.vertex_arc[v]) << "vertex " << v << ", piece " << piece;
    }
    // The pipeline with a budget that only the streamed plan fits (twice
    // its 20 B/voxel: half is left to the rest of the run).
    const uint64_t n = volume.voxel_count();
    const TopologyResult r = compute_contour_tree(volume, {}, {}, 2 * contour_tree_work_bytes(n, TreeMemoryPlan::Streamed));
    EXPECT_EQ(r.plan, TreeMemoryPlan::Streamed);
    EXPECT_EQ(r.tree.node_vertex, whole.node_vertex);
    EXPECT_EQ(r.tree.arc_lo, whole.arc_lo);
    EXPECT_EQ(compute_contour_tree(volume).plan, TreeMemoryPlan::Parallel);
}

TEST(OrderPieces, PlanIsTheFastestThatTakesHalfTheBudget)
{
    const uint64_t n = 1000;
    EXPECT_EQ(choose_tree_memory_plan(n, ARBOR_VOXEL_I16, 2 * 27 * n), TreeMemoryPlan::Parallel);
    EXPECT_EQ(choose_tree_memory_plan(n, ARBOR_VOXEL_I16, 2 * 27 * n - 1), TreeMemoryPlan::Sequential);
    EXPECT_EQ(choose_tree_memory_plan(n, ARBOR_VOXEL_I16, 2 * 23 * n - 1), TreeMemoryPlan::Streamed);
    EXPECT_EQ(choose_tree_memory_plan(n, ARBOR_VOXEL_I16, 0), TreeMemoryPlan::Streamed);
    EXPECT_EQ(choose_tree_memory_plan(n, ARBOR_VOXEL_F32, 2 * 23 * n - 1), TreeMemoryPlan::Sequential);
    EXPECT_EQ(least_contour_tree_work_bytes(n, ARBOR_VOXEL_U16), 20 * n);
    EXPECT_EQ(least_contour_tree_work_bytes(n, ARBOR_VOXEL_F32), 23 * n);
    // A whole-body CT on a 24 GB machine (about 23 GB available) streams.
    EXPECT_EQ(choose_tree_memory_plan(512ull * 512 * 2000, ARBOR_VOXEL_I16, 23'000'000'000ull), TreeMemoryPlan::Streamed);
    EXPECT_EQ(choose_tree_memory_plan(512ull * 512 * 300, ARBOR_VOXEL_I16, 23'000'000'000ull), TreeMemoryPlan::Parallel);
}

TEST(UninitializedBuffer, ShrinkToKeepsTheFrontAndReturnsTheRest)
{
    for (const std::size_t n : {std::size_t{10}, std::size_t{1} << 20}) { // operator new, and mapped
        UninitializedBuffer<uint64_t> wide(n);
        uint32_t *narrow = reinterpret_cast<uint32_t *>(wide.data());
        for (std::size_t i = 0; i < n; ++i)
            narrow[i] = static_cast<uint32_t>(i * 7 + 3);
        const UninitializedBuffer<uint32_t> kept = std::move(wide).shrink_to<uint32_t>(n);
        EXPECT_TRUE(wide.empty());
        ASSERT_EQ(kept.size(), n);
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_EQ(kept[i], i * 7 + 3);
    }
    UninitializedBuffer<uint32_t> small(4);
    EXPECT_THROW(std::move(small).shrink_to<uint64_t>(3), std::length_error);
}

} // namespace
} // namespace arbor
