// test_cell_sample.cpp - the gradient a ray-caster sample reads from its
// cell (plugins/raycast/cell_sample.hpp).  SampleGradient, four corners at
// a time with SSE2, against the definition computed here in double
// precision one corner at a time: the corners' gradients (unit direction x
// magnitude, the magnitude a quarter up for the direction) weighted
// trilinearly.  IsotropicGradient, on thick slices, against the volume
// actually resampled to isotropic voxels: central differences there,
// interpolated trilinearly.
#include "cell_sample.hpp"

#include <gtest/gtest.h>

#include <array>

#include <cmath>
#include <random>

using arbor::raycast::Cell;
using arbor::raycast::IsotropicGradient;
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

namespace {

// The gradient (per mm) at voxel position p of `g` (spacing `spacing`,
// axis-aligned) computed the long way: g resampled trilinearly to voxels
// of its finest spacing, central differences at those voxels (one-sided at
// the faces, as compute_normals), weighted trilinearly at p.
std::array<double, 3> resampled_gradient(const VoxelGrid &g, const std::array<double, 3> &spacing,
                                         const std::array<double, 3> &p)
{
    const double h = std::min({spacing[0], spacing[1], spacing[2]});
    const int64_t size[3] = {g.nx, g.ny, g.nz};
    std::array<int64_t, 3> factor{}, fine{};
    for (int a = 0; a < 3; ++a) {
        factor[a] = spacing[a] >= 2 * h ? std::llround(spacing[a] / h) : 1; // even below twice the finest
        fine[a] = (size[a] - 1) * factor[a] + 1;
    }
    // The original field, trilinear, at fine voxel q.
    const auto value = [&](std::array<int64_t, 3> q) {
        int64_t c[3];
        double f[3];
        for (int a = 0; a < 3; ++a) {
            q[a] = std::clamp<int64_t>(q[a], 0, fine[a] - 1);
            c[a] = std::min(q[a] / factor[a], std::max<int64_t>(size[a] - 2, 0));
            f[a] = static_cast<double>(q[a] - c[a] * factor[a]) / static_cast<double>(factor[a]);
        }
        double sum = 0;
        for (int m = 0; m < 8; ++m) {
            double w = 1;
            int64_t at[3];
            for (int a = 0; a < 3; ++a) {
                const bool up = (m >> a) & 1;
                w *= up ? f[a] : 1 - f[a];
                at[a] = std::min(c[a] + (up ? 1 : 0), size[a] - 1);
            }
            sum += w * g.value[g.index(at[0], at[1], at[2])];
        }
        return sum;
    };
    // Central differences at fine voxel q, per mm.
    const auto difference = [&](const std::array<int64_t, 3> &q, int a) {
        std::array<int64_t, 3> lo = q, hi = q;
        lo[a] = std::max<int64_t>(q[a] - 1, 0);
        hi[a] = std::min(q[a] + 1, fine[a] - 1);
        const double fine_spacing = spacing[a] / static_cast<double>(factor[a]);
        return (value(hi) - value(lo)) / (static_cast<double>(hi[a] - lo[a]) * fine_spacing);
    };
    std::array<int64_t, 3> c{};
    double f[3];
    for (int a = 0; a < 3; ++a) {
        const double x = p[a] * static_cast<double>(factor[a]);
        c[a] = std::min(static_cast<int64_t>(x), fine[a] - 2);
        f[a] = x - static_cast<double>(c[a]);
    }
    std::array<double, 3> sum{};
    for (int m = 0; m < 8; ++m) {
        double w = 1;
        std::array<int64_t, 3> q{};
        for (int a = 0; a < 3; ++a) {
            const bool up = (m >> a) & 1;
            w *= up ? f[a] : 1 - f[a];
            q[a] = c[a] + (up ? 1 : 0);
        }
        for (int a = 0; a < 3; ++a)
            sum[a] += w * difference(q, a);
    }
    return sum;
}

void expect_resampled(const std::array<int64_t, 3> &size, const std::array<double, 3> &spacing, std::mt19937 &rng,
                      int samples)
{
    VoxelGrid g = random_grid(size[0], size[1], size[2], rng);
    const double h = std::min({spacing[0], spacing[1], spacing[2]});
    for (int a = 0; a < 3; ++a)
        g.resample_scale[a] = spacing[a] >= 2 * h ? static_cast<float>(spacing[a] / h) : 1.0f;
    g.flat_gradient = 0;
    g.gradient_scale = 1;
    const float inverse[9] = {static_cast<float>(1 / spacing[0]), 0, 0, 0, static_cast<float>(1 / spacing[1]), 0,
                              0, 0, static_cast<float>(1 / spacing[2])};
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0; n < samples; ++n) {
        int64_t c[3];
        float f[3];
        for (int a = 0; a < 3; ++a) {
            c[a] = std::uniform_int_distribution<int64_t>(0, size[a] - 2)(rng);
            // Within a fine spacing of the slices (where the differences
            // are blended) as often as between them.
            const double u = unit(rng);
            f[a] = static_cast<float>(u < 0.05 ? 0.0 : u > 0.95 ? 1.0 : unit(rng));
        }
        const std::size_t base = g.index(c[0], c[1], c[2]);
        const Cell cell(g, base, g.strides(), f[0], f[1], f[2]);
        const IsotropicGradient at(g, base, g.strides(), c, inverse, cell);
        const std::array<double, 3> expected =
            resampled_gradient(g, spacing, {c[0] + double{f[0]}, c[1] + double{f[1]}, c[2] + double{f[2]}});
        for (int a = 0; a < 3; ++a)
            ASSERT_NEAR(at.direction[a], expected[a], 1e-3 * (1 + std::fabs(expected[a])))
                << "axis " << a << " cell " << c[0] << "," << c[1] << "," << c[2] << " at " << f[0] << "," << f[1]
                << "," << f[2];
    }
}

} // namespace

TEST(IsotropicGradient, IsTheGradientOfTheVolumeResampledToIsotropicVoxels)
{
    std::mt19937 rng(52);
    expect_resampled({6, 5, 5}, {1.0, 1.0, 6.0}, rng, 3000);  // thick slices
    expect_resampled({5, 6, 4}, {0.5, 0.5, 1.5}, rng, 3000);  // a ratio of 3
    expect_resampled({4, 6, 5}, {3.0, 1.0, 1.0}, rng, 3000);  // the thick axis is i
    expect_resampled({5, 4, 6}, {1.0, 2.0, 4.0}, rng, 3000);  // two thick axes
    expect_resampled({2, 2, 2}, {1.0, 1.0, 5.0}, rng, 1000);  // one cell: one-sided everywhere
}

TEST(IsotropicGradient, OnEvenAxesItIsTheVoxelsCentralDifferencesWeighedTrilinearly)
{
    std::mt19937 rng(53);
    expect_resampled({6, 5, 7}, {0.8, 0.8, 0.8}, rng, 3000);
    expect_resampled({6, 5, 7}, {1.0, 1.2, 1.9}, rng, 3000); // under twice the finest: even
}
