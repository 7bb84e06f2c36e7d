// The time-left estimate of a long stage: a constant rate is extrapolated
// exactly, nothing is promised too early, and a new or restarted stage
// starts its clock again.
#include "pipeline/time_left.hpp"

#include <gtest/gtest.h>

namespace arbor::pipeline {

TEST(TimeLeft, ExtrapolatesAConstantRate)
{
    StageClock clock;
    EXPECT_FALSE(clock.observe("sorting", 0.0, 100.0));
    // 10 % a second: at 30 % after 3 s, 7 s are left.
    const std::optional<double> left = clock.observe("sorting", 0.3, 103.0);
    ASSERT_TRUE(left);
    EXPECT_DOUBLE_EQ(*left, 7.0);
    EXPECT_DOUBLE_EQ(*clock.observe("sorting", 0.5, 105.0), 5.0);
}

TEST(TimeLeft, SaysNothingTooEarlyOrWhenDone)
{
    StageClock clock;
    clock.observe("merging trees", 0.0, 0.0);
    EXPECT_FALSE(clock.observe("merging trees", 0.5, 1.5)) << "under 2 s";
    EXPECT_FALSE(clock.observe("merging trees", 0.01, 5.0)) << "fraction went back: restarted";
    EXPECT_FALSE(clock.observe("merging trees", 0.015, 9.0)) << "under 2 %";
    EXPECT_FALSE(clock.observe("merging trees", 1.0, 10.0)) << "done";
}

TEST(TimeLeft, ANewStageStartsTheClockAgain)
{
    StageClock clock;
    clock.observe("sorting", 0.0, 0.0);
    ASSERT_TRUE(clock.observe("sorting", 0.9, 9.0));
    EXPECT_FALSE(clock.observe("join and split trees", 0.1, 10.0));
    EXPECT_DOUBLE_EQ(*clock.observe("join and split trees", 0.2, 14.0), 16.0);
}

TEST(TimeLeft, ReadsLikeATerminalTool)
{
    EXPECT_EQ(format_time_left(3.2), "a few seconds left");
    EXPECT_EQ(format_time_left(44.6), "about 45 s left");
    EXPECT_EQ(format_time_left(130.0), "about 2 min 10 s left");
    EXPECT_EQ(format_time_left(3900.0), "about 1 h 05 min left");
}

} // namespace arbor::pipeline
