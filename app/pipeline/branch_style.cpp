#include "branch_style.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace arbor::pipeline {

std::shared_ptr<const TransferFunctions> styled(std::shared_ptr<const TransferFunctions> functions,
                                                const arbor_branch_tree &tree,
                                                const std::map<int64_t, BranchStyle> &styles)
{
    if (styles.empty() || tree.branch_count != functions->branch_count())
        return functions;
    std::vector<const BranchStyle *> of(tree.branch_count, nullptr);
    bool any = false;
    for (uint32_t b = 0; b < tree.branch_count; ++b)
        if (const auto s = styles.find(tree.extremum_vertex[b]); s != styles.end() && !(s->second == BranchStyle{})) {
            of[b] = &s->second;
            any = true;
        }
    if (!any)
        return functions;
    // A copy (every opacity scaled by 1 keeps it), then each styled branch's table.
    std::shared_ptr<TransferFunctions> out =
        functions->with_optical_depth(std::vector<double>(functions->branch_count(), 1.0));
    const uint32_t n = functions->lut_size();
    std::vector<float> lut(std::size_t{n} * 4);
    for (uint32_t b = 0; b < tree.branch_count; ++b) {
        if (!of[b])
            continue;
        const BranchStyle &s = *of[b];
        std::copy(out->lut(b), out->lut(b) + lut.size(), lut.begin());
        for (uint32_t i = 0; i < n; ++i) {
            float *e = &lut[std::size_t{i} * 4];
            const double a = std::clamp<double>(e[3], 0.0, 1.0);
            e[3] = s.visible ? static_cast<float>(1 - std::pow(1 - a, std::max(0.0, s.opacity))) : 0.0f;
            if (s.color)
                for (int k = 0; k < 3; ++k)
                    e[k] = static_cast<float>(std::clamp((*s.color)[k], 0.0, 1.0));
        }
        out->assign(b, out->domain(b), lut.data());
    }
    return out;
}

} // namespace arbor::pipeline
