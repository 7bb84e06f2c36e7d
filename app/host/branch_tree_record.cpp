#include "branch_tree_record.hpp"

#include <cmath>

namespace arbor {

BranchTreeRecord::BranchTreeRecord(const topology::ContourTree &tree, const topology::BranchDecomposition &d,
                                   const topology::SimplificationCut &cut, const Volume &volume,
                                   const std::vector<topology::LabelShape> *shapes)
{
    static_assert(BranchTreeArrays::kMeasureCount == topology::kMeasureCount);
    const std::size_t n = cut.kept.size(), m = topology::kMeasureCount;
    BranchTreeArrays &a = arrays_;
    a.resize(n);
    a.importance.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const topology::Branch &b = d.branches[cut.kept[k]];
        a.parent[k] = cut.kept_parent[k];
        a.kind[k] = b.kind == topology::BranchKind::Minimum ? ARBOR_EXTREMUM_MINIMUM : ARBOR_EXTREMUM_MAXIMUM;
        const uint32_t sv = tree.node_vertex[b.saddle_node], ev = tree.node_vertex[b.extremum_node];
        a.saddle_vertex[k] = sv;
        a.extremum_vertex[k] = ev;
        a.saddle_value[k] = volume.value(sv);
        a.extremum_value[k] = volume.value(ev);
        const auto sp = volume.geometry().position_of(sv), ep = volume.geometry().position_of(ev);
        for (int i = 0; i < 3; ++i) {
            a.saddle_position[3 * k + i] = sp[i];
            a.extremum_position[3 * k + i] = ep[i];
        }
        for (std::size_t c = 0; c < m; ++c) {
            a.measures[k * m + c] = b.measures[c];
            a.relative[k * m + c] = d.relative(cut.kept[k], static_cast<int>(c));
        }
        a.importance[k] = std::isfinite(b.importance) ? b.importance : 1.0;
    }
    a.value_scale = volume.mapping().scale;
    a.value_offset = volume.mapping().offset;
    a.value_unit = volume.mapping().unit;
    if (shapes) {
        a.extra_ids = {ARBOR_MEASURE_THICKNESS, ARBOR_MEASURE_COMPACTNESS};
        a.extra.assign(2, std::vector<double>(n, 0.0));
        for (std::size_t k = 0; k < n && k < shapes->size(); ++k) {
            a.extra[0][k] = (*shapes)[k].thickness_mm;
            a.extra[1][k] = (*shapes)[k].compactness;
        }
    }
    a.link();
}

} // namespace arbor
