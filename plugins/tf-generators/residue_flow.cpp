#include "residue_flow.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::tf {

namespace {

double triangle_area(double p, double v, double hv)
{
    return 0.5 * std::sqrt((hv * p) * (hv * p) + (v * p) * (v * p) + (hv * v) * (hv * v));
}

// The sibling factors g_sb * g_sd of the children of one branch (6.7-6.9):
// g_sb is ITri on the siblings' measures, each normalised by the siblings'
// maximum, rescaled so the strongest sibling gets 1; g_sd grows from ε at the
// saddle farthest from the children's extrema to 1 at the nearest (the
// saddle value, mirrored for minima).  An only child gets 1.
void sibling_factors(const sdk::BranchTreeView &tree, std::span<const uint32_t> siblings, uint32_t p_col,
                     uint32_t v_col, uint32_t hv_col, double floor, std::vector<double> &factor)
{
    if (siblings.size() == 1) {
        factor[siblings[0]] = 1.0;
        return;
    }
    double max_p = 0, max_v = 0, max_hv = 0, s_min = INFINITY, s_max = -INFINITY;
    const auto s_of = [&](uint32_t b) { return tree.is_minimum(b) ? -tree.saddle_value(b) : tree.saddle_value(b); };
    for (uint32_t b : siblings) {
        max_p = std::max(max_p, tree.relative(b, p_col));
        max_v = std::max(max_v, tree.relative(b, v_col));
        max_hv = std::max(max_hv, tree.relative(b, hv_col));
        s_min = std::min(s_min, s_of(b));
        s_max = std::max(s_max, s_of(b));
    }
    const auto norm = [](double x, double max) { return max > 0 ? x / max : 1.0; };
    double best = 0;
    for (uint32_t b : siblings) {
        factor[b] = triangle_area(norm(tree.relative(b, p_col), max_p), norm(tree.relative(b, v_col), max_v),
                                  norm(tree.relative(b, hv_col), max_hv));
        best = std::max(best, factor[b]);
    }
    for (uint32_t b : siblings) {
        const double g_sb = best > 0 ? factor[b] / best : 1.0;
        const double g_sd = s_max > s_min ? floor + (1.0 - floor) * (s_of(b) - s_min) / (s_max - s_min) : 1.0;
        factor[b] = g_sb * g_sd;
    }
}

} // namespace

std::vector<OpacityRange> residue_flow(const sdk::BranchTreeView &tree, const FlowParameters &p)
{
    const uint32_t n = tree.size();
    const uint32_t p_col = tree.require_column(ARBOR_MEASURE_PERSISTENCE);
    const uint32_t v_col = tree.require_column(ARBOR_MEASURE_VOLUME);
    const uint32_t hv_col = tree.require_column(ARBOR_MEASURE_HYPERVOLUME);
    uint32_t max_depth = 0;
    for (uint32_t b = 0; b < n; ++b)
        max_depth = std::max(max_depth, tree.depth(b));
    // One band per level; the thesis divides by d_max, which over-fills the
    // range by a level.
    const double level_band = p.alpha_range / (max_depth + 1.0);

    std::vector<double> factor(n, 1.0), residue(n, 0.0), band(n, 0.0);
    for (uint32_t b = 0; b < n; ++b)
        if (!tree.children(b).empty())
            sibling_factors(tree, tree.children(b), p_col, v_col, hv_col, p.sibling_floor, factor);

    std::vector<OpacityRange> out(n);
    for (uint32_t b = 0; b < n; ++b) { // parents first
        const int32_t parent = tree.parent(b);
        const double inflow = level_band + (parent >= 0 ? residue[static_cast<uint32_t>(parent)] : 0.0);
        const std::size_t children = tree.children(b).size();
        const double loss =
            children == 0 ? 0.0
                          : std::clamp(p.flow_rate * tree.relative(b, p_col) / (p.conductivity * children), 0.0, 1.0);
        out[b].head_loss = loss;
        out[b].absorbed = inflow * (1.0 - loss);
        residue[b] = inflow * loss;
        band[b] = out[b].absorbed * factor[b];
        out[b].low = parent >= 0 ? out[static_cast<uint32_t>(parent)].high : p.alpha_min;
        out[b].high = out[b].low + band[b];
    }
    return out;
}

} // namespace arbor::tf
