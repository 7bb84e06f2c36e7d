#include "branch_colours.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::tf {

const LightVivid &ColourCache::find(double hue, double lightness, double vividness)
{
    const auto key = std::make_tuple(hue, lightness, vividness);
    auto it = colours_.find(key);
    if (it == colours_.end()) {
        if (colours_.size() > 100000)
            colours_.clear(); // a bound, not an LRU: trees this large regenerate anyway
        it = colours_.emplace(key, colour_for(hue, lightness, vividness)).first;
    }
    return it->second;
}

std::vector<double> vividness_importance(const sdk::BranchTreeView &tree)
{
    const uint32_t n = tree.size();
    const uint32_t p = tree.require_column(ARBOR_MEASURE_PERSISTENCE);
    const uint32_t v = tree.require_column(ARBOR_MEASURE_VOLUME);
    const uint32_t hv = tree.require_column(ARBOR_MEASURE_HYPERVOLUME);
    std::vector<double> itri(n, 0.0), out(n, 1.0);
    for (uint32_t b = 0; b < n; ++b) {
        const double x = tree.relative(b, p), y = tree.relative(b, v), z = tree.relative(b, hv);
        itri[b] = 0.5 * std::sqrt((z * x) * (z * x) + (y * x) * (y * x) + (z * y) * (z * y));
    }
    for (uint32_t parent = 0; parent < n; ++parent) {
        double best = 0.0;
        for (uint32_t c : tree.children(parent))
            best = std::max(best, itri[c]);
        for (uint32_t c : tree.children(parent))
            out[c] = best > 0.0 ? itri[c] / best : 1.0;
    }
    return out;
}

namespace {

// Per branch its hue within its family's sector: the family's branches in
// root-down order spread evenly over it.
std::vector<double> family_hues(const std::vector<TissueChoice> &tissues)
{
    const std::vector<HueFamily> &families = hue_families();
    std::vector<std::size_t> members(families.size(), 0), rank(tissues.size(), 0);
    for (std::size_t b = 0; b < tissues.size(); ++b)
        rank[b] = members[tissues[b].family]++;
    std::vector<double> hues(tissues.size());
    for (std::size_t b = 0; b < tissues.size(); ++b) {
        const HueFamily &f = families[tissues[b].family];
        const double t = (static_cast<double>(rank[b]) + 0.5) / static_cast<double>(members[tissues[b].family]);
        hues[b] = std::fmod(f.hue + f.width * (t - 0.5) + 360.0, 360.0);
    }
    return hues;
}

// x in [from_low, from_high] to the same place in [to_low, to_high].
double remap(double x, double from_low, double from_high, double to_low, double to_high)
{
    const double t = from_high > from_low ? std::clamp((x - from_low) / (from_high - from_low), 0.0, 1.0) : 0.5;
    return to_low + t * (to_high - to_low);
}

} // namespace

std::vector<BranchColour> branch_colours(const sdk::BranchTreeView &tree, const ColourSettings &s,
                                         const arbor_depiction *depiction, ColourCache &cache,
                                         const std::vector<TissueChoice> *tissues)
{
    const uint32_t n = tree.size();
    uint32_t max_depth = 0;
    for (uint32_t b = 0; b < n; ++b)
        max_depth = std::max(max_depth, tree.depth(b));
    // Subtree sizes, children after parents: sum backwards.
    std::vector<double> subtree(n, 1.0);
    for (uint32_t b = n; b-- > 1;)
        subtree[static_cast<uint32_t>(tree.parent(b))] += subtree[b];
    const std::vector<double> importance = vividness_importance(tree);
    const bool by_tissue = tissues && tissues->size() == n;
    // Branches are in root-down order.
    const std::vector<double> hues = by_tissue ? family_hues(*tissues) : s.hues.spread(n);

    std::vector<BranchColour> out(n);
    for (uint32_t b = 0; b < n; ++b) {
        const double depth = max_depth > 0 ? static_cast<double>(tree.depth(b)) / max_depth : 0.0;
        BranchColour &c = out[b];
        c.hue = hues[b];
        c.lightness = s.lightness_max - depth * (1.0 - subtree[b] / n) * (s.lightness_max - s.lightness_min);
        // 6.15 scales V_min by the importance too, which would make small
        // branches less vivid than the root (the outermost structure); here
        // importance scales only the rise with depth, so V stays in
        // [V_min, V_max] and the root is the least vivid.
        c.vividness = s.vividness_min + depth * (s.vividness_max - s.vividness_min) * importance[b];
        if (by_tissue) {
            const HueFamily &f = hue_families()[(*tissues)[b].family];
            c.lightness = remap(c.lightness, s.lightness_min, s.lightness_max, f.lightness_min, f.lightness_max);
            c.vividness = remap(c.vividness, s.vividness_min, s.vividness_max, f.vividness_min, f.vividness_max);
        }
        if (depiction) {
            if (!std::isnan(depiction->hue[b]))
                c.hue = depiction->hue[b];
            c.vividness *= std::clamp(static_cast<double>(depiction->saturation[b]), 0.0, 1.0);
        }
        c.rgb = cache.find(c.hue, c.lightness, c.vividness).rgb;
    }
    return out;
}

} // namespace arbor::tf
