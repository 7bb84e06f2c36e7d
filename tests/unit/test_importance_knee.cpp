// The automatic branch count: the knee of log importance against rank.
#include "topology/importance_knee.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace arbor::topology {
namespace {

BranchDecomposition with_importances(const std::vector<double> &importance)
{
    BranchDecomposition d;
    d.branches.resize(importance.size() + 1);
    d.branches[0].importance = INFINITY; // the root
    for (std::size_t b = 0; b < importance.size(); ++b)
        d.branches[b + 1].importance = importance[b];
    return d;
}

TEST(ImportanceKnee, FindsTheBendIntoTheNoiseTail)
{
    for (std::size_t strong : {8u, 12u, 20u}) {
        std::vector<double> imp;
        for (std::size_t r = 0; r < strong; ++r)
            imp.push_back(0.5 * std::pow(0.8, static_cast<double>(r))); // structures
        for (std::size_t r = 0; r < 300; ++r)
            imp.push_back(1e-6 * (1.0 - 0.002 * static_cast<double>(r))); // noise
        const KneeChoice k = knee_branch_count(with_importances(imp));
        // The structures, the knee point itself (here the first of the tail;
        // on gradual real curves, the weakest structure) and the root.
        EXPECT_EQ(k.keep, strong + 2) << strong;
        EXPECT_EQ(k.considered, 50u);
    }
}

TEST(ImportanceKnee, ClampsAndHandlesTinyTrees)
{
    EXPECT_EQ(knee_branch_count(with_importances({0.5, 0.4, 1e-9})).keep, 4u); // all there is
    std::vector<double> two_then_noise{0.9, 0.8};
    for (int r = 0; r < 100; ++r)
        two_then_noise.push_back(1e-7);
    EXPECT_EQ(knee_branch_count(with_importances(two_then_noise)).keep, 6u); // the minimum
    EXPECT_EQ(knee_branch_count(with_importances({})).keep, 1u);
}

} // namespace
} // namespace arbor::topology
