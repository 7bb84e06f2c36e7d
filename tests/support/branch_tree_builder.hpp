// branch_tree_builder.hpp - arbor_branch_tree records built by hand (for
// tests with known neighbourhoods and depths) or at random (for benchmarks
// of tree-only plugins at 10 ... 10^4 branches).
#pragma once

#include "host/branch_tree_arrays.hpp"

#include <algorithm>
#include <cstdint>
#include <array>
#include <map>
#include <random>
#include <vector>

namespace arbor::test {

class BranchTreeBuilder {
public:
    // parent[0] = -1, parent[b] < b.  Every branch starts as a maximum over
    // [b, b + 1] with relative measures 0.5 (the root's are 1).
    explicit BranchTreeBuilder(const std::vector<int32_t> &parent)
    {
        const std::size_t n = parent.size();
        a_.resize(n);
        a_.parent = parent;
        for (std::size_t b = 0; b < n; ++b) {
            a_.saddle_value[b] = static_cast<double>(b);
            a_.extremum_value[b] = static_cast<double>(b) + 1.0;
            a_.saddle_vertex[b] = a_.extremum_vertex[b] = static_cast<int64_t>(b);
        }
        std::fill(a_.relative.begin(), a_.relative.end(), 0.5);
        std::fill(a_.relative.begin(), a_.relative.begin() + BranchTreeArrays::kMeasureCount, 1.0);
        a_.importance.assign(n, 0.5);
    }

    // A random tree of n branches: each hangs off one of the 8 branches
    // before it (deep trees, as noisy scans give).
    static BranchTreeBuilder random(uint32_t n, uint64_t seed)
    {
        std::mt19937_64 rng(seed);
        std::vector<int32_t> parent(n, -1);
        for (uint32_t b = 1; b < n; ++b) {
            std::uniform_int_distribution<uint32_t> back(1, std::min<uint32_t>(b, 8));
            parent[b] = static_cast<int32_t>(b - back(rng));
        }
        BranchTreeBuilder t(parent);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (uint32_t b = 1; b < n; ++b) {
            const double s = 100.0 * u(rng);
            t.set(b, s, s + 50.0 * u(rng), u(rng) < 0.3, u(rng), u(rng) * u(rng), u(rng) * u(rng));
        }
        return t;
    }

    // Relative persistence p, volume v (also as mm^3) and hypervolume hv
    // (also as relative hypervolume); the absolute measures are the same.
    void set(uint32_t b, double saddle, double extremum, bool minimum, double p, double v, double hv)
    {
        a_.saddle_value[b] = saddle;
        a_.extremum_value[b] = extremum;
        a_.kind[b] = minimum ? ARBOR_EXTREMUM_MINIMUM : ARBOR_EXTREMUM_MAXIMUM;
        const double row[BranchTreeArrays::kMeasureCount] = {p, v, v, hv, hv};
        std::copy(row, row + BranchTreeArrays::kMeasureCount, a_.relative.begin() + BranchTreeArrays::kMeasureCount * b);
    }

    // The host's label-geometry columns (thickness in mm, compactness).
    void set_shape(uint32_t b, double thickness_mm, double compactness)
    {
        if (a_.extra_ids.empty()) {
            a_.extra_ids = {ARBOR_MEASURE_THICKNESS, ARBOR_MEASURE_COMPACTNESS};
            a_.extra.assign(2, std::vector<double>(a_.parent.size(), 0.0));
        }
        a_.extra[0][b] = thickness_mm;
        a_.extra[1][b] = compactness;
    }
    // Absolute measures, when they should differ from the relative ones:
    // persistence, volume and relative hypervolume (shape choice reads them).
    void set_absolute(uint32_t b, double p, double v, double rhv)
    {
        absolute_[b] = {p, v, rhv};
    }

    const arbor_branch_tree &record()
    {
        a_.measures = a_.relative;
        for (const auto &[b, m] : absolute_) {
            a_.measures[BranchTreeArrays::kMeasureCount * b + 0] = m[0];
            a_.measures[BranchTreeArrays::kMeasureCount * b + 1] = m[1];
            a_.measures[BranchTreeArrays::kMeasureCount * b + 4] = m[2];
        }
        return a_.link();
    }

private:
    BranchTreeArrays a_;
    std::map<uint32_t, std::array<double, 3>> absolute_;
};

} // namespace arbor::test
