// test_cell_sample.cpp - the gradient a ray-caster sample reads from its
// cell (plugins/raycast/cell_sample.hpp), four corners at a time with SSE2,
// against the definition computed here in double precision one corner at a
// time: the corners' gradients (unit direction x magnitude, the magnitude a
// quarter up for the direction) weighted trilinearly.
#include "cell_sample.hpp"

#include <gtest/gtest.h>

#include <array>

#include <cmath>
#include <random>

using arbor::raycast::Cell;
using arbor::raycast::SampleGradient;
using arbor::raycast::Surface;
using arbor::raycast::VoxelGrid;

namespace {

VoxelGrid random_grid(int64_t nx, int64_t ny, int64_t nz, std::mt19937 &rng)
{
    VoxelGrid g;
    g.nx = nx, g.ny = ny, g.nz = nz;
    const std::size_t n = static_cast<std::size_t>(nx * ny * nz);
    g.value.resize(n);
    g.surface.resize(n);
    std::uniform_int_distribution<int> normal(-127, 127), magnitude(0, 255);
    std::uniform_real_distribution<float> value(-1000.0f, 1000.0f);
    for (std::size_t v = 0; v < n; ++v) {
        g.value[v] = value(rng);
        // Extremes included: -127 and 255 catch a sign or a shift lost.
        g.surface[v] = {{static_cast<int8_t>(normal(rng)), static_cast<int8_t>(normal(rng)),
                         static_cast<int8_t>(normal(rng))},
                        static_cast<uint8_t>(magnitude(rng))};
    }
    return g;
}

struct Expected {
    double normal[3] = {0, 0, 0};
    double magnitude = 0;
};

Expected definition(const VoxelGrid &g, int64_t i, int64_t j, int64_t k, double fx, double fy, double fz)
{
    const VoxelGrid::Strides s = g.strides();
    double sum[3] = {0, 0, 0};
    Expected e;
    for (int m = 0; m < 8; ++m) {
        const double w = (m & 1 ? fx : 1 - fx) * (m & 2 ? fy : 1 - fy) * (m & 4 ? fz : 1 - fz);
        const std::size_t at = g.index(i, j, k) + static_cast<std::size_t>((m & 1 ? s.i : 0) + (m & 2 ? s.j : 0) +
                                                                           (m & 4 ? s.k : 0));
        const Surface &q = g.surface[at];
        e.magnitude += w * q.gradient;
        for (int a = 0; a < 3; ++a)
            sum[a] += w * (q.gradient + 0.25) * q.normal[a];
    }
    const double length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    for (int a = 0; a < 3; ++a)
        e.normal[a] = length > 0 ? sum[a] / length : 0.0;
    return e;
}

void expect_definition(const VoxelGrid &g, std::mt19937 &rng, int samples)
{
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const VoxelGrid::Strides s = g.strides();
    for (int n = 0; n < samples; ++n) {
        const int64_t i = std::uniform_int_distribution<int64_t>(0, std::max<int64_t>(g.nx - 2, 0))(rng);
        const int64_t j = std::uniform_int_distribution<int64_t>(0, std::max<int64_t>(g.ny - 2, 0))(rng);
        const int64_t k = std::uniform_int_distribution<int64_t>(0, std::max<int64_t>(g.nz - 2, 0))(rng);
        // Faces and corners of the cell as well as its inside.
        double f[3];
        for (double &x : f) {
            const double u = unit(rng);
            x = u < 0.1 ? 0.0 : u > 0.9 ? 1.0 : unit(rng);
        }
        const Cell cell(g, g.index(i, j, k), s, static_cast<float>(f[0]), static_cast<float>(f[1]),
                        static_cast<float>(f[2]));
        const SampleGradient fast(g, g.index(i, j, k), s, cell);
        const SampleGradient scalar(SampleGradient::Scalar{}, g, g.index(i, j, k), s, cell);
        const Expected e = definition(g, i, j, k, cell.fx, cell.fy, cell.fz);
        ASSERT_NEAR(fast.magnitude, e.magnitude, 1e-3) << "cell " << i << "," << j << "," << k;
        ASSERT_NEAR(scalar.magnitude, e.magnitude, 1e-3);
        for (int a = 0; a < 3; ++a) {
            ASSERT_NEAR(fast.normal[a], e.normal[a], 1e-4) << "axis " << a << " cell " << i << "," << j << "," << k;
            ASSERT_NEAR(scalar.normal[a], e.normal[a], 1e-4);
        }
    }
}

} // namespace

TEST(SampleGradientSse, WeighsEveryCornerAsTheDefinition)
{
    std::mt19937 rng(49);
    const VoxelGrid g = random_grid(7, 5, 6, rng);
    expect_definition(g, rng, 20000);
}

TEST(SampleGradientSse, FlatAxesOfOneVoxelWeighTheirOnlyVoxel)
{
    std::mt19937 rng(50);
    for (const auto &[nx, ny, nz] : {std::array<int64_t, 3>{1, 6, 5}, {6, 1, 5}, {6, 5, 1}, {1, 1, 7}})
        expect_definition(random_grid(nx, ny, nz, rng), rng, 2000);
}

TEST(SampleGradientSse, AVanishingGradientHasNoDirection)
{
    std::mt19937 rng(51);
    VoxelGrid g = random_grid(2, 2, 2, rng);
    for (std::size_t v = 0; v < 8; ++v)
        g.surface[v] = {{0, 0, 0}, 0};
    const Cell cell(g, 0, g.strides(), 0.3f, 0.6f, 0.9f);
    const SampleGradient at(g, 0, g.strides(), cell);
    EXPECT_EQ(at.magnitude, 0.0f);
    for (const float n : at.normal)
        EXPECT_EQ(n, 0.0f);
}
