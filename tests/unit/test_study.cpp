// The study layer's scores: the assignment against brute force, and the
// contingency, Dice, precision, recall and matchings on hand-built label
// maps whose answers are worked out here.
#include "study/assignment.hpp"
#include "study/region_scores.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace arbor::study {
namespace {

// The best total over every one-to-one matching (rows to distinct columns
// or to nothing), by enumerating the permutations of the padded columns.
double brute_force_best(const std::vector<double> &w, std::size_t rows, std::size_t cols)
{
    const std::size_t n = std::max(rows, cols);
    std::vector<std::size_t> perm(n);
    std::iota(perm.begin(), perm.end(), 0);
    double best = 0;
    do {
        double total = 0;
        for (std::size_t r = 0; r < rows; ++r)
            if (perm[r] < cols)
                total += w[r * cols + perm[r]];
        best = std::max(best, total);
    } while (std::next_permutation(perm.begin(), perm.end()));
    return best;
}

TEST(Assignment, MatchesBruteForceOnRandomMatrices)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::uniform_int_distribution<int> size(1, 6), sparse(0, 3);
    int checked = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const std::size_t rows = static_cast<std::size_t>(size(rng)), cols = static_cast<std::size_t>(size(rng));
        std::vector<double> w(rows * cols);
        for (double &x : w)
            x = sparse(rng) == 0 ? 0.0 : uniform(rng); // zeros: pairs that are no match
        const std::vector<long> match = max_weight_assignment(w, rows, cols);
        ASSERT_EQ(match.size(), rows);
        double total = 0;
        std::vector<bool> taken(cols, false);
        for (std::size_t r = 0; r < rows; ++r) {
            if (match[r] < 0)
                continue;
            const std::size_t c = static_cast<std::size_t>(match[r]);
            ASSERT_LT(c, cols);
            ASSERT_FALSE(taken[c]) << "column " << c << " matched twice";
            taken[c] = true;
            ASSERT_GT(w[r * cols + c], 0.0) << "a zero-weight pair reported as a match";
            total += w[r * cols + c];
        }
        EXPECT_NEAR(total, brute_force_best(w, rows, cols), 1e-9) << rows << " x " << cols << ", trial " << trial;
        ++checked;
    }
    EXPECT_EQ(checked, 400);
}

TEST(Assignment, RefusesBadWeights)
{
    EXPECT_THROW(max_weight_assignment({1.0, -1.0}, 1, 2), std::invalid_argument);
    EXPECT_THROW(max_weight_assignment({1.0}, 1, 2), std::invalid_argument);
    EXPECT_TRUE(max_weight_assignment({}, 0, 3).empty());
}

Volume label_volume(const std::vector<int> &labels)
{
    Geometry g;
    g.dims = {static_cast<int64_t>(labels.size()), 1, 1};
    Volume v = Volume::allocate(ARBOR_VOXEL_I32, g, {}, uint64_t{1} << 30);
    std::copy(labels.begin(), labels.end(), v.as<int32_t>());
    return v;
}

TEST(RegionScores, TruthLabelsAreNumberedInAscendingOrder)
{
    const TruthLabels t = read_truth(label_volume({0, 7, 7, 3, 0, 3, 3, 12}));
    EXPECT_EQ(t.labels, (std::vector<uint32_t>{3, 7, 12}));
    EXPECT_EQ(t.voxels, (std::vector<uint64_t>{3, 2, 1}));
    EXPECT_EQ(t.index, (std::vector<uint32_t>{0, 2, 2, 1, 0, 1, 1, 3}));
    EXPECT_THROW(read_truth(label_volume({0, -1})), std::invalid_argument);
    EXPECT_THROW(read_truth(label_volume({0, 1, 2, 3}), 2), std::invalid_argument);
}

// Three truth structures of 4 voxels each; the simplification keeps the
// root (region 0), region 1 spanning structures A and B (under-segmented)
// and region 2 holding half of B: both matchings agree there.  Then one
// region lumps all three: best match credits it three times, one-to-one
// once.
TEST(RegionScores, OneToOneCreditsARegionOnceWhereBestMatchCreditsItTwice)
{
    //                                 A A A A  B B B B  C C C C  background
    const TruthLabels truth = read_truth(label_volume({1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 0, 0}));
    const std::vector<uint32_t> kept = {1, 1, 1, 1, 1, 1, 2, 2, 0, 0, 0, 0, 0, 0};
    const Contingency table = count_overlaps(truth, kept, 3);
    EXPECT_EQ(table.at(1, 1), 4u); // region 1 n A
    EXPECT_EQ(table.at(1, 2), 2u); // region 1 n B
    EXPECT_EQ(table.at(2, 2), 2u);
    EXPECT_EQ(table.at(0, 3), 4u);
    EXPECT_EQ(table.at(0, 0), 2u);
    EXPECT_EQ(table.region_voxels(1), 6u);

    const TruthMatches m = match_regions(table, truth);
    // A: region 1, Dice 2*4/(4+6) = 0.8, precision 4/6, recall 1.
    EXPECT_EQ(m.best[0].region, 1);
    EXPECT_DOUBLE_EQ(m.best[0].dice, 0.8);
    EXPECT_DOUBLE_EQ(m.best[0].precision, 4.0 / 6.0);
    EXPECT_DOUBLE_EQ(m.best[0].recall, 1.0);
    // B: region 1 (2*2/10 = 0.4) loses to region 2 (2*2/(4+2) = 0.667).
    EXPECT_EQ(m.best[1].region, 2);
    EXPECT_DOUBLE_EQ(m.best[1].dice, 4.0 / 6.0);
    // C: the root region holds it (2*4/(4+6) = 0.8) in both matchings.
    EXPECT_EQ(m.best[2].region, 0);
    EXPECT_EQ(m.one_to_one[0].region, 1);
    EXPECT_EQ(m.one_to_one[1].region, 2);
    EXPECT_EQ(m.one_to_one[2].region, 0);

    // One region for all three: best match credits it three times, one-to-one once.
    const std::vector<uint32_t> lump = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0};
    const TruthMatches lumped = match_regions(count_overlaps(truth, lump, 2), truth);
    int best_credits = 0, one_to_one_credits = 0;
    for (std::size_t t = 0; t < 3; ++t) {
        best_credits += lumped.best[t].region == 1;
        one_to_one_credits += lumped.one_to_one[t].region == 1;
    }
    EXPECT_EQ(best_credits, 3);
    EXPECT_EQ(one_to_one_credits, 1);
}

TEST(RegionScores, SubtreeRegionsAddEveryKeptDescendant)
{
    const TruthLabels truth = read_truth(label_volume({1, 1, 1, 1, 0, 0}));
    // Region 2 is a child of region 1, which is a child of the root.
    const std::vector<uint32_t> kept = {1, 1, 2, 2, 0, 0};
    const Contingency exclusive = count_overlaps(truth, kept, 3);
    const Contingency subtree = subtree_regions(exclusive, {-1, 0, 1});
    EXPECT_EQ(subtree.at(1, 1), 4u);
    EXPECT_EQ(subtree.region_voxels(1), 4u);
    EXPECT_EQ(subtree.region_voxels(0), 6u);
    EXPECT_DOUBLE_EQ(match_regions(exclusive, truth).best[0].dice, 2.0 * 2 / (4 + 2));
    EXPECT_DOUBLE_EQ(match_regions(subtree, truth).best[0].dice, 1.0);
    EXPECT_THROW(subtree_regions(exclusive, {-1, 2, 1}), std::invalid_argument); // a cycle
}

TEST(RegionScores, RefusesMismatchedSizesAndLabels)
{
    const TruthLabels truth = read_truth(label_volume({1, 0}));
    EXPECT_THROW(count_overlaps(truth, std::vector<uint32_t>{0, 0, 0}, 1), std::invalid_argument);
    EXPECT_THROW(count_overlaps(truth, std::vector<uint32_t>{0, 5}, 2), std::invalid_argument);
}

} // namespace
} // namespace arbor::study
