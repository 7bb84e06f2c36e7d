#include "branch_tree_arrays.hpp"

namespace arbor {

const char *const BranchTreeArrays::kMeasureIds[kMeasureCount] = {
    ARBOR_MEASURE_PERSISTENCE, ARBOR_MEASURE_VOLUME, ARBOR_MEASURE_VOLUME_MM3, ARBOR_MEASURE_HYPERVOLUME,
    ARBOR_MEASURE_RELATIVE_HYPERVOLUME};

void BranchTreeArrays::resize(std::size_t n)
{
    parent.assign(n, 0);
    if (n > 0)
        parent[0] = -1;
    kind.assign(n, ARBOR_EXTREMUM_MAXIMUM);
    saddle_vertex.assign(n, 0);
    extremum_vertex.assign(n, 0);
    saddle_value.assign(n, 0.0);
    extremum_value.assign(n, 0.0);
    saddle_position.assign(3 * n, 0.0);
    extremum_position.assign(3 * n, 0.0);
    measures.assign(n * kMeasureCount, 0.0);
    relative.assign(n * kMeasureCount, 0.0);
}

const arbor_branch_tree &BranchTreeArrays::link()
{
    const std::size_t n = parent.size();
    depth_.assign(n, 0);
    child_offsets_.assign(n + 1, 0);
    for (std::size_t b = 1; b < n; ++b) {
        depth_[b] = depth_[static_cast<std::size_t>(parent[b])] + 1; // parents come first
        ++child_offsets_[static_cast<std::size_t>(parent[b]) + 1];
    }
    for (std::size_t b = 0; b < n; ++b)
        child_offsets_[b + 1] += child_offsets_[b];
    children_.assign(n > 0 ? n - 1 : 0, 0);
    std::vector<uint32_t> next(child_offsets_.begin(), child_offsets_.end() - 1);
    for (std::size_t b = 1; b < n; ++b)
        children_[next[static_cast<std::size_t>(parent[b])]++] = static_cast<uint32_t>(b);

    record_ = {};
    record_.struct_size = sizeof record_;
    record_.branch_count = static_cast<uint32_t>(n);
    record_.measure_count = kMeasureCount;
    record_.parent = parent.data();
    record_.depth = depth_.data();
    record_.child_offsets = child_offsets_.data();
    record_.children = children_.data();
    record_.extremum_kind = kind.data();
    record_.saddle_vertex = saddle_vertex.data();
    record_.extremum_vertex = extremum_vertex.data();
    record_.saddle_value = saddle_value.data();
    record_.extremum_value = extremum_value.data();
    record_.saddle_position = saddle_position.data();
    record_.extremum_position = extremum_position.data();
    record_.measure_ids = kMeasureIds;
    record_.measures = measures.data();
    record_.relative_measures = relative.data();
    if (!extra_ids.empty()) {
        // One table of every column, each extra one relative to the root's.
        const std::size_t m = kMeasureCount + extra_ids.size();
        all_measures_.assign(n * m, 0.0);
        all_relative_.assign(n * m, 0.0);
        for (std::size_t b = 0; b < n; ++b) {
            for (std::size_t c = 0; c < kMeasureCount; ++c) {
                all_measures_[b * m + c] = measures[b * kMeasureCount + c];
                all_relative_[b * m + c] = relative[b * kMeasureCount + c];
            }
            for (std::size_t e = 0; e < extra_ids.size(); ++e) {
                const double root = extra[e].empty() ? 0.0 : extra[e][0];
                all_measures_[b * m + kMeasureCount + e] = extra[e][b];
                all_relative_[b * m + kMeasureCount + e] = root > 0 ? extra[e][b] / root : 0.0;
            }
        }
        ids_.assign(kMeasureIds, kMeasureIds + kMeasureCount);
        for (const std::string &id : extra_ids)
            ids_.push_back(id.c_str());
        record_.measure_count = static_cast<uint32_t>(m);
        record_.measure_ids = ids_.data();
        record_.measures = all_measures_.data();
        record_.relative_measures = all_relative_.data();
    }
    record_.importance = importance.empty() ? nullptr : importance.data();
    record_.value_scale = value_scale;
    record_.value_offset = value_offset;
    unit_.assign(value_unit.c_str(), value_unit.c_str() + value_unit.size() + 1);
    record_.value_unit = unit_.data();
    return record_;
}

} // namespace arbor
