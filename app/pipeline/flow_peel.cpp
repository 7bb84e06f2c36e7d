#include "flow_peel.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::pipeline {

std::vector<double> flow_peel(const arbor_branch_tree &tree, double q_ratio)
{
    const uint32_t n = tree.branch_count;
    std::vector<double> peel(n, 1.0);
    if (!(q_ratio > 0) || q_ratio == 1.0 || n < 2)
        return peel;
    // Subtree heights: a parent's index is below its children's
    // (arbor_branch_tree lists parents first), so one pass from the end.
    std::vector<uint32_t> height(n, 0);
    for (uint32_t b = n; b-- > 1;) {
        const int32_t p = tree.parent[b];
        if (p >= 0)
            height[static_cast<uint32_t>(p)] = std::max(height[static_cast<uint32_t>(p)], height[b] + 1);
    }
    const double top = *std::max_element(height.begin(), height.end());
    if (top <= 0)
        return peel;
    for (uint32_t b = 0; b < n; ++b)
        peel[b] = std::pow(1.0 / q_ratio, height[b] / top);
    return peel;
}

std::vector<double> peeled_scale(const std::vector<double> &scale, const std::vector<double> &peel)
{
    std::vector<double> out(scale);
    for (std::size_t b = 0; b < out.size() && b < peel.size(); ++b)
        out[b] *= peel[b];
    return out;
}

} // namespace arbor::pipeline
