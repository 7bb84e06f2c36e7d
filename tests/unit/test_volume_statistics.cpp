// Value range, moments, non-finite samples and histogram of a volume.
#include "core/volume.hpp"
#include "core/volume_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace arbor {
namespace {

Volume make(arbor_voxel_type type, int64_t n)
{
    Geometry g;
    g.dims = {n, 1, 1};
    return Volume::allocate(type, g, {}, uint64_t{1} << 30);
}

TEST(VolumeStatistics, KnownValues)
{
    Volume v = make(ARBOR_VOXEL_I16, 4);
    int16_t *p = v.as<int16_t>();
    p[0] = -1024;
    p[1] = 0;
    p[2] = 0;
    p[3] = 1024;
    const VolumeStatistics s = compute_statistics(v, 4);
    EXPECT_EQ(s.min, -1024);
    EXPECT_EQ(s.max, 1024);
    EXPECT_EQ(s.mean, 0);
    EXPECT_NEAR(s.stddev, std::sqrt(2 * 1024.0 * 1024 / 4), 1e-9);
    EXPECT_EQ(s.histogram, (std::vector<int64_t>{1, 0, 2, 1}));
    EXPECT_EQ(s.finite_count, 4);
}

TEST(VolumeStatistics, CountsNonFiniteSamplesAndWhereTheyAre)
{
    Volume v = make(ARBOR_VOXEL_F32, 5);
    float *p = v.as<float>();
    p[0] = 1;
    p[1] = std::numeric_limits<float>::quiet_NaN();
    p[2] = 3;
    p[3] = std::numeric_limits<float>::infinity();
    p[4] = 2;
    const VolumeStatistics s = compute_statistics(v, 8);
    EXPECT_EQ(s.nan_count, 1);
    EXPECT_EQ(s.infinite_count, 1);
    EXPECT_EQ(s.first_non_finite, 1);
    EXPECT_EQ(s.min, 1);
    EXPECT_EQ(s.max, 3);
    EXPECT_EQ(s.mean, 2);
}

TEST(VolumeStatistics, LargeOffsetsKeepTheVarianceExact)
{
    Volume v = make(ARBOR_VOXEL_F64, 3);
    double *p = v.as<double>();
    p[0] = 1e9 + 1;
    p[1] = 1e9 + 2;
    p[2] = 1e9 + 3;
    const VolumeStatistics s = compute_statistics(v);
    EXPECT_NEAR(s.stddev, std::sqrt(2.0 / 3.0), 1e-6);
    EXPECT_NEAR(s.quantile(0.5), 1e9 + 2, 0.1);
}

} // namespace
} // namespace arbor
