// The body region (core/body_region.hpp) on volumes made to know the answer:
// a body with air inside it (a lung) lying on a thin plate (a headrest),
// a thin plate touching the body, and a scan that is only thin vessels.
#include "core/body_region.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace arbor {
namespace {

// 1 mm voxels, i fastest; `f` gives each voxel's value and label.
struct Scene {
    std::array<int64_t, 3> dims{80, 80, 40};
    Volume volume;
    std::vector<uint32_t> labels;

    explicit Scene(const std::function<std::pair<double, uint32_t>(int64_t, int64_t, int64_t)> &f)
        : volume([&] {
              Geometry g;
              g.dims = dims;
              return Volume::allocate(ARBOR_VOXEL_F32, g, {}, uint64_t{1} << 30);
          }())
    {
        labels.resize(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
        std::size_t v = 0;
        for (int64_t k = 0; k < dims[2]; ++k)
            for (int64_t j = 0; j < dims[1]; ++j)
                for (int64_t i = 0; i < dims[0]; ++i, ++v) {
                    const auto [value, label] = f(i, j, k);
                    volume.as<float>()[v] = static_cast<float>(value);
                    labels[v] = label;
                }
    }
};

constexpr double kAir = -1000, kTissue = 40, kPlate = -100;

// Labels: 0 air, 1 the body's tissue, 2 the lung inside it, 3 a plate
// `gap` voxels below the body (0: touching it), 3 voxels thick.
std::pair<double, uint32_t> body_on_plate(int64_t i, int64_t j, int64_t k, int64_t gap)
{
    const double r = std::hypot(static_cast<double>(i) - 40, static_cast<double>(j) - 36);
    if (r < 8)
        return {kAir, 2};
    if (r < 28)
        return {kTissue, 1};
    const int64_t top = 36 + 28 + gap;
    if (j >= top && j < top + 3 && k >= 0)
        return {kPlate, 3};
    return {kAir, 0};
}

TEST(BodyRegion, APlateBelowTheBodyIsOutsideAndTheLungInside)
{
    for (const int64_t gap : {4, 0}) {
        const Scene s([&](int64_t i, int64_t j, int64_t k) { return body_on_plate(i, j, k, gap); });
        const BodyRegion body(s.volume, -900);
        const std::vector<double> out = body.outside_shares(s.labels, 4);
        // The body's tissue inside but for the rim of 2 mm cells that are
        // mostly air.
        EXPECT_LT(out[1], 0.05) << "gap " << gap;
        EXPECT_EQ(out[2], 0.0) << "the lung is inside the body, gap " << gap;
        EXPECT_GT(out[3], 0.8) << "the plate is outside, gap " << gap;
        EXPECT_GT(out[0], 0.8) << "the air around is outside, gap " << gap;
    }
}

TEST(BodyRegion, NoBackgroundOrNoBodyLeavesEverythingInside)
{
    const Scene s([](int64_t i, int64_t j, int64_t k) { return body_on_plate(i, j, k, 4); });
    EXPECT_EQ(BodyRegion(s.volume, std::nan("")).outside_shares(s.labels, 4), std::vector<double>(4, 0.0));
    // Thin vessels in air, in many pieces: no body to speak of.
    const Scene vessels([](int64_t i, int64_t j, int64_t) -> std::pair<double, uint32_t> {
        return (i % 10 < 2 && j % 10 < 2) ? std::pair{300.0, 1u} : std::pair{0.0, 0u};
    });
    const std::vector<double> out = BodyRegion(vessels.volume, 50).outside_shares(vessels.labels, 2);
    EXPECT_EQ(out[1], 0.0);
}

} // namespace
} // namespace arbor
