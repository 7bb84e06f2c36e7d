#include "region_scores.hpp"

#include "assignment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace arbor::study {

TruthLabels read_truth(const Volume &truth, std::size_t max_labels)
{
    const std::size_t n = truth.voxel_count();
    TruthLabels t;
    t.index.resize(n);
    std::unordered_map<uint32_t, uint32_t> slot; // label -> provisional index + 1
    std::vector<uint32_t> seen;
    for (std::size_t v = 0; v < n; ++v) {
        const double x = truth.value(v);
        if (!(x >= 0) || x != std::floor(x) || x > 4294967295.0)
            throw std::invalid_argument("the ground-truth labels must be non-negative integers (voxel " +
                                        std::to_string(v) + " holds " + std::to_string(x) + ")");
        const uint32_t label = static_cast<uint32_t>(x);
        if (label == 0) {
            t.index[v] = 0;
            continue;
        }
        auto [it, added] = slot.try_emplace(label, static_cast<uint32_t>(seen.size() + 1));
        if (added) {
            seen.push_back(label);
            if (seen.size() > max_labels)
                throw std::invalid_argument("the ground truth has more than " + std::to_string(max_labels) +
                                            " labels; a label map of structures is expected");
        }
        t.index[v] = it->second;
    }
    // Number the labels in ascending order.
    t.labels = seen;
    std::sort(t.labels.begin(), t.labels.end());
    std::vector<uint32_t> renumber(seen.size() + 1, 0);
    for (std::size_t i = 0; i < seen.size(); ++i)
        renumber[i + 1] = static_cast<uint32_t>(std::lower_bound(t.labels.begin(), t.labels.end(), seen[i]) -
                                                t.labels.begin() + 1);
    t.voxels.assign(t.labels.size(), 0);
    for (uint32_t &i : t.index) {
        i = renumber[i];
        if (i)
            ++t.voxels[i - 1];
    }
    return t;
}

uint64_t Contingency::region_voxels(std::size_t region) const
{
    uint64_t sum = 0;
    for (std::size_t c = 0; c <= truths; ++c)
        sum += at(region, c);
    return sum;
}

Contingency count_overlaps(const TruthLabels &truth, std::span<const uint32_t> kept_labels, std::size_t regions)
{
    if (kept_labels.size() != truth.index.size())
        throw std::invalid_argument("the ground truth has " + std::to_string(truth.index.size()) +
                                    " voxels, the label map " + std::to_string(kept_labels.size()) +
                                    ": they must have the same dims");
    Contingency table;
    table.regions = regions;
    table.truths = truth.labels.size();
    table.count.assign(regions * (table.truths + 1), 0);
    const std::size_t width = table.truths + 1;
    for (std::size_t v = 0; v < kept_labels.size(); ++v) {
        const uint32_t k = kept_labels[v];
        if (k >= regions)
            throw std::invalid_argument("voxel " + std::to_string(v) + " has kept label " + std::to_string(k) +
                                        " of " + std::to_string(regions));
        ++table.count[k * width + truth.index[v]];
    }
    return table;
}

Contingency subtree_regions(const Contingency &exclusive, const std::vector<int32_t> &kept_parent)
{
    if (kept_parent.size() != exclusive.regions)
        throw std::invalid_argument("subtree_regions: one parent per region is needed");
    Contingency out = exclusive;
    const std::size_t width = exclusive.truths + 1;
    // Every region's counts go to each of its kept ancestors.
    for (std::size_t k = 0; k < exclusive.regions; ++k) {
        std::size_t steps = 0;
        for (int32_t a = kept_parent[k]; a >= 0; a = kept_parent[static_cast<std::size_t>(a)]) {
            if (static_cast<std::size_t>(a) >= exclusive.regions || ++steps > exclusive.regions)
                throw std::invalid_argument("subtree_regions: the kept parents are not a tree");
            for (std::size_t c = 0; c < width; ++c)
                out.count[static_cast<std::size_t>(a) * width + c] += exclusive.count[k * width + c];
        }
    }
    return out;
}

namespace {

RegionMatch scored(const Contingency &table, const TruthLabels &truth, std::size_t t, long region)
{
    RegionMatch m;
    if (region < 0)
        return m;
    const std::size_t k = static_cast<std::size_t>(region);
    m.region = region;
    m.overlap = table.at(k, t + 1);
    m.region_voxels = table.region_voxels(k);
    const double both = static_cast<double>(m.overlap);
    m.dice = 2.0 * both / static_cast<double>(truth.voxels[t] + m.region_voxels);
    m.precision = m.region_voxels ? both / static_cast<double>(m.region_voxels) : 0.0;
    m.recall = truth.voxels[t] ? both / static_cast<double>(truth.voxels[t]) : 0.0;
    return m;
}

} // namespace

TruthMatches match_regions(const Contingency &table, const TruthLabels &truth)
{
    const std::size_t T = truth.labels.size(), K = table.regions;
    if (table.truths != T)
        throw std::invalid_argument("match_regions: the table was counted against another truth");
    std::vector<double> dice(T * K, 0.0);
    std::vector<uint64_t> region(K);
    for (std::size_t k = 0; k < K; ++k)
        region[k] = table.region_voxels(k);
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t k = 0; k < K; ++k)
            dice[t * K + k] = 2.0 * static_cast<double>(table.at(k, t + 1)) /
                              static_cast<double>(truth.voxels[t] + region[k]);
    TruthMatches out;
    const std::vector<long> assigned = max_weight_assignment(dice, T, K);
    for (std::size_t t = 0; t < T; ++t) {
        long best = -1;
        for (std::size_t k = 0; k < K; ++k)
            if (dice[t * K + k] > 0 && (best < 0 || dice[t * K + k] > dice[t * K + static_cast<std::size_t>(best)]))
                best = static_cast<long>(k);
        out.best.push_back(scored(table, truth, t, best));
        out.one_to_one.push_back(scored(table, truth, t, assigned[t]));
    }
    return out;
}

} // namespace arbor::study
