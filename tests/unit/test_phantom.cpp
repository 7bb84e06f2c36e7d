// The built-in phantom: deterministic, and it makes the thesis' point —
// nested structures whose value ranges overlap.
#include "io/phantom.hpp"
#include "core/volume_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace arbor {
namespace {

double value_at(const Volume &v, double x_mm, double y_mm, double z_mm)
{
    // Nearest voxel to an LPS position (the phantom grid is axis-aligned).
    const Geometry &g = v.geometry();
    const auto idx = [&](double p, int a) {
        return static_cast<int64_t>(std::lround((p - g.origin[a]) / g.spacing[a]));
    };
    const int64_t i = idx(x_mm, 0), j = idx(y_mm, 1), k = idx(z_mm, 2);
    return v.value(i + g.dims[0] * (j + g.dims[1] * k));
}

// LPS position (mm) of a recipe coordinate (fractions of half the field of view).
double mm(const io::PhantomRecipe &r, double fraction)
{
    return fraction * r.field_of_view_mm / 2;
}

const io::PhantomStructure &structure(const io::PhantomRecipe &r, const std::string &name)
{
    for (const auto &s : r.structures)
        if (s.name == name)
            return s;
    throw std::runtime_error("no structure " + name);
}

TEST(Phantom, IsDeterministic)
{
    const io::PhantomRecipe r = io::builtin_phantom("head");
    io::PhantomOptions o;
    o.size = 48;
    o.noise_sigma = 7;
    o.blobs = 5;
    o.seed = 42;
    const Volume a = io::make_phantom(r, o), b = io::make_phantom(r, o);
    ASSERT_EQ(a.byte_size(), b.byte_size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.byte_size()), 0);
    o.seed = 43;
    const Volume c = io::make_phantom(r, o);
    EXPECT_NE(std::memcmp(a.data(), c.data(), a.byte_size()), 0);
}

TEST(Phantom, GeometryIsCentredOnTheOrigin)
{
    io::PhantomOptions o;
    o.size = 64;
    const Volume v = io::make_phantom(io::builtin_phantom("head"), o);
    const Geometry &g = v.geometry();
    EXPECT_EQ(g.dims, (std::array<int64_t, 3>{64, 64, 64}));
    EXPECT_DOUBLE_EQ(g.spacing[0], 200.0 / 64);
    const auto first = g.position(0, 0, 0), last = g.position(63, 63, 63);
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(first[a] + last[a], 0.0, 1e-9);
}

TEST(Phantom, StructuresAreNestedWithOverlappingValues)
{
    const io::PhantomRecipe r = io::builtin_phantom("head");
    io::PhantomOptions o;
    o.size = 128;
    const Volume v = io::make_phantom(r, o);
    const auto at = [&](double x, double y, double z) { return value_at(v, mm(r, x), mm(r, y), mm(r, z)); };

    // Walk from outside to the centre of the right hemisphere along +/- x.
    EXPECT_EQ(at(-0.95, 0, 0), r.background);            // air
    EXPECT_NEAR(at(-0.705, 0, 0), 700, 1);               // scalp shell
    EXPECT_NEAR(at(-0.645, 0, 0), 80, 1);                // skull shell
    EXPECT_NEAR(at(-0.60, 0, 0), 150, 1);                // CSF
    EXPECT_NEAR(at(-0.47, 0, 0), 470, 1);                // grey matter
    const io::PhantomStructure &ventricle = structure(r, "ventricle");
    EXPECT_NEAR(at(ventricle.center[0], ventricle.center[1], ventricle.center[2]), 150, 1);
    const io::PhantomStructure &tumour = structure(r, "tumour");
    const io::PhantomStructure &white = structure(r, "right-white-matter");
    const double tumour_peak = at(tumour.center[0], tumour.center[1], tumour.center[2]);
    const double white_peak = at(white.center[0], white.center[1], white.center[2]);
    // The tumour is a bump on the grey matter, lower than the white matter's
    // peak: its values lie inside the brain's range (no global 1D transfer
    // function separates them) yet it is a maximum of its own.
    EXPECT_GT(tumour_peak, white.edge + 50);
    EXPECT_LT(tumour_peak, white_peak - 40);
    for (int a = 0; a < 3; ++a) {
        std::array<double, 3> p = tumour.center;
        p[a] += 1.5 * tumour.radii[a];
        EXPECT_GT(tumour_peak - at(p[0], p[1], p[2]), 50) << "axis " << a;
        p[a] -= 3.0 * tumour.radii[a];
        EXPECT_GT(tumour_peak - at(p[0], p[1], p[2]), 50) << "axis " << a;
    }
}

TEST(Phantom, NoiseAndBlobsChangeTheStatistics)
{
    const io::PhantomRecipe r = io::builtin_phantom("head");
    io::PhantomOptions clean;
    clean.size = 64;
    io::PhantomOptions noisy = clean;
    noisy.noise_sigma = 10;
    noisy.blobs = 20;
    const VolumeStatistics a = compute_statistics(io::make_phantom(r, clean));
    const VolumeStatistics b = compute_statistics(io::make_phantom(r, noisy));
    EXPECT_EQ(a.max, 700);
    EXPECT_GT(b.stddev, a.stddev);
}

TEST(Phantom, RefusesBadOptionsAndRecipes)
{
    const io::PhantomRecipe r = io::builtin_phantom("head");
    io::PhantomOptions o;
    o.size = 4;
    EXPECT_THROW(io::make_phantom(r, o), std::invalid_argument);
    o.size = 32;
    o.noise_sigma = -1;
    EXPECT_THROW(io::make_phantom(r, o), std::invalid_argument);
    EXPECT_THROW(io::builtin_phantom("torso"), std::invalid_argument);
    EXPECT_THROW(io::parse_phantom_recipe("{not json"), std::invalid_argument);
    EXPECT_THROW(io::parse_phantom_recipe(
                     R"({"name":"x","structures":[{"name":"a","center":[0,0],"radii":[1,1,1],"edge":0,"peak":1}]})"),
                 std::invalid_argument);
}

} // namespace
} // namespace arbor
