#include "branch_importance.hpp"

#include "host/simplifier_importance.hpp"

#include <algorithm>

namespace arbor::pipeline {

std::vector<double> branch_importance(const PluginCatalog &catalog, const PluginSetting &simplifier,
                                      const topology::BranchDecomposition &d, const ValueMapping &mapping)
{
    PluginInstance instance = catalog.create(simplifier.id);
    apply_setting(instance, simplifier);
    const topology::ImportanceFn importance = simplifier_importance(instance, mapping);
    const std::size_t n = d.branches.size();
    std::vector<double> out;
    out.reserve(n > 0 ? n - 1 : 0);
    std::vector<topology::BranchMeasures> batch;
    std::vector<double> values;
    for (std::size_t start = 1; start < n; start += 4096) {
        batch.clear();
        for (std::size_t b = start; b < std::min(n, start + 4096); ++b) {
            const topology::Branch &branch = d.branches[b];
            topology::BranchMeasures m;
            m.absolute = branch.measures;
            for (int c = 0; c < topology::kMeasureCount; ++c)
                m.relative[static_cast<std::size_t>(c)] = d.relative(static_cast<uint32_t>(b), c);
            m.kind = branch.kind;
            m.saddle_value = branch.saddle_value;
            m.extremum_value = branch.extremum_value;
            batch.push_back(m);
        }
        values.assign(batch.size(), 0.0);
        importance(batch, values);
        out.insert(out.end(), values.begin(), values.end());
    }
    return out;
}

} // namespace arbor::pipeline
