// The header check is the host's guard against hostile or broken headers: it
// must refuse them with a message before any allocation happens.
#include "core/volume.hpp"
#include "core/volume_header.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace arbor {
namespace {

arbor_volume header(int64_t nx, int64_t ny, int64_t nz, arbor_voxel_type type = ARBOR_VOXEL_U8)
{
    arbor_volume h{};
    h.struct_size = sizeof(h);
    h.voxel_type = type;
    h.dims[0] = nx;
    h.dims[1] = ny;
    h.dims[2] = nz;
    h.spacing[0] = h.spacing[1] = h.spacing[2] = 1.0;
    h.direction[0] = h.direction[4] = h.direction[8] = 1.0;
    h.value_scale = 1.0;
    h.value_unit = "";
    return h;
}

constexpr uint64_t kLimit = uint64_t{1} << 30;

TEST(VolumeHeader, AcceptsOrdinaryVolumes)
{
    EXPECT_EQ(check_volume_header(header(256, 256, 128), kLimit), "");
    EXPECT_EQ(check_volume_header(header(1, 1, 1, ARBOR_VOXEL_F64), kLimit), "");
}

TEST(VolumeHeader, RefusesZeroAndNegativeDims)
{
    EXPECT_NE(check_volume_header(header(0, 64, 64), kLimit).find("at least 1"), std::string::npos);
    EXPECT_NE(check_volume_header(header(64, -5, 64), kLimit).find("at least 1"), std::string::npos);
}

TEST(VolumeHeader, RefusesProductsThatOverflow)
{
    const int64_t big = std::numeric_limits<int64_t>::max() / 2;
    const std::string m = check_volume_header(header(big, big, big), kLimit);
    EXPECT_NE(m.find("most Arbor handles"), std::string::npos) << m;
}

TEST(VolumeHeader, RefusesHugeClaimsBeforeAllocating)
{
    // 100000^3 voxels: 10^15, more than 32-bit voxel indices allow.
    EXPECT_NE(check_volume_header(header(100000, 100000, 100000), kLimit), "");
    // Fits the index range but not the memory limit.
    const std::string m = check_volume_header(header(2048, 2048, 512, ARBOR_VOXEL_F32), kLimit);
    EXPECT_NE(m.find("this host allows"), std::string::npos) << m;
    EXPECT_THROW(Volume::allocate(header(2048, 2048, 512, ARBOR_VOXEL_F32), kLimit),
                 std::invalid_argument);
}

TEST(VolumeHeader, RefusesUnknownTypesAndBadGeometry)
{
    EXPECT_NE(check_volume_header(header(4, 4, 4, 99), kLimit).find("unknown voxel type"),
              std::string::npos);
    arbor_volume h = header(4, 4, 4);
    h.spacing[1] = 0.0;
    EXPECT_NE(check_volume_header(h, kLimit).find("spacing"), std::string::npos);
    h = header(4, 4, 4);
    h.spacing[2] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(check_volume_header(h, kLimit), "");
    h = header(4, 4, 4);
    h.direction[8] = 0.0; // third axis collapses
    EXPECT_NE(check_volume_header(h, kLimit).find("degenerate"), std::string::npos);
    h = header(4, 4, 4);
    h.value_scale = 0.0;
    EXPECT_NE(check_volume_header(h, kLimit).find("value mapping"), std::string::npos);
}

TEST(Volume, PositionsFollowSpacingDirectionAndOrigin)
{
    Geometry g;
    g.dims = {4, 5, 6};
    g.spacing = {0.5, 2.0, 3.0};
    g.origin = {10.0, 20.0, 30.0};
    g.direction = {1, 0, 0, 0, -1, 0, 0, 0, 1}; // j runs anterior
    const auto p = g.position(2, 1, 1);
    EXPECT_DOUBLE_EQ(p[0], 11.0);
    EXPECT_DOUBLE_EQ(p[1], 18.0);
    EXPECT_DOUBLE_EQ(p[2], 33.0);
    const auto q = g.position_of(2 + 4 * (1 + 5 * 1));
    EXPECT_EQ(p, q);
}

} // namespace
} // namespace arbor
