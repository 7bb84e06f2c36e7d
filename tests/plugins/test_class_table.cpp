// test_class_table.cpp - the CPU ray caster's classification table
// (plugins/raycast/classification.hpp).  lookup_shown(), the early test that
// lets transparent samples skip the table, against lookup() itself over
// every value near every entry's rounding edge: it may answer "certainly
// transparent" only where lookup() reads an entry of zero opacity, and
// otherwise must read the same entry.
#include "classification.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using arbor::raycast::ClassTable;

namespace {

// Opacity per entry of each branch: runs of zero opacity at either end, in
// the middle, everywhere or nowhere, in random lengths.
struct Tables {
    static constexpr uint32_t kEntries = 64;
    std::vector<double> domain;
    std::vector<float> lut;

    void add(double lo, double hi, const std::vector<float> &alpha)
    {
        domain.push_back(lo);
        domain.push_back(hi);
        for (float a : alpha)
            lut.insert(lut.end(), {0.5f, 0.25f, 1.0f, a});
    }

    arbor_tf_set set()
    {
        arbor_tf_set s{};
        s.struct_size = sizeof s;
        s.branch_count = static_cast<uint32_t>(domain.size() / 2);
        s.lut_size = kEntries;
        s.opacity_unit_distance = 1.0;
        s.domain = domain.data();
        s.lut = lut.data();
        return s;
    }
};

std::vector<float> opacities(std::mt19937 &rng, uint32_t first, uint32_t end, bool gap)
{
    std::vector<float> alpha(Tables::kEntries, 0.0f);
    std::uniform_real_distribution<float> a(0.01f, 1.0f);
    for (uint32_t e = first; e < end; ++e)
        alpha[e] = a(rng);
    if (gap && end > first + 4)
        alpha[(first + end) / 2] = alpha[(first + end) / 2 + 1] = 0.0f;
    return alpha;
}

// Values at, just below and just above each entry's rounding edges, and
// beyond the domain on both sides (infinity too, unless the domain is
// empty: there infinity times a scale of 0 is NaN, which lookup_shown
// calls transparent, as the next test asks).
std::vector<float> probes(double lo, double hi)
{
    const float far = hi > lo ? std::numeric_limits<float>::infinity() : 1e30f;
    std::vector<float> v{-far, far, static_cast<float>(lo - 1e6), static_cast<float>(hi + 1e6)};
    const double width = hi > lo ? (hi - lo) / (Tables::kEntries - 1) : 1.0;
    for (int e = -2; e <= static_cast<int>(Tables::kEntries) + 1; ++e)
        for (double at : {e - 0.5, e + 0.0, e + 0.5}) {
            const float x = static_cast<float>(lo + at * width);
            float below = x, above = x;
            for (int n = 0; n < 4; ++n) {
                v.push_back(below = std::nextafter(below, -std::numeric_limits<float>::infinity()));
                v.push_back(above = std::nextafter(above, std::numeric_limits<float>::infinity()));
            }
            v.push_back(x);
        }
    return v;
}

} // namespace

TEST(ClassTable, LookupShownAnswersTransparentOnlyWhereTheEntryIs)
{
    std::mt19937 rng(49);
    Tables t;
    const uint32_t n = Tables::kEntries;
    // first..end of the entries that show, and a gap in the middle or not.
    const std::vector<std::array<uint32_t, 3>> shapes = {
        {0, n, 0}, {0, n, 1}, {10, n, 0}, {0, 40, 1}, {10, 40, 0}, {10, 40, 1},
        {1, n - 1, 0}, {31, 32, 0}, {0, 1, 0}, {n - 1, n, 0}, {0, 0, 0}};
    for (const auto &[first, end, gap] : shapes) {
        t.add(-1000.0, 3000.0, opacities(rng, first, end, gap != 0));
        t.add(0.25, 0.75, opacities(rng, first, end, gap != 0));
        t.add(7.0, 7.0, opacities(rng, first, end, gap != 0)); // an empty domain: every value reads entry 0
    }
    arbor_tf_set set = t.set();
    ClassTable table;
    table.build(set, 0.5);
    std::size_t checked = 0, early = 0;
    for (uint32_t b = 0; b < set.branch_count; ++b)
        for (float value : probes(t.domain[2 * b], t.domain[2 * b + 1])) {
            const float *entry = table.lookup(b, value);
            const float *shown = table.lookup_shown(b, value);
            ++checked;
            if (!shown) {
                ++early;
                EXPECT_EQ(entry[3], 0.0f) << "branch " << b << " value " << value;
            } else {
                EXPECT_EQ(shown, entry) << "branch " << b << " value " << value;
            }
        }
    // The early answer is actually taken (a test that never takes it would
    // pass with lookup_shown = lookup).
    EXPECT_GT(early, checked / 10);
    EXPECT_EQ(checked, set.branch_count * probes(0, 1).size());
}

TEST(ClassTable, LookupShownTakesNanForTransparent)
{
    Tables t;
    t.add(0.0, 1.0, std::vector<float>(Tables::kEntries, 0.5f));
    arbor_tf_set set = t.set();
    ClassTable table;
    table.build(set, 1.0);
    EXPECT_EQ(table.lookup_shown(0, std::numeric_limits<float>::quiet_NaN()), nullptr);
    EXPECT_NE(table.lookup_shown(0, 0.5f), nullptr);
}
