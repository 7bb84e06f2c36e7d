// branch_tree_arrays.hpp - owning storage behind an arbor_branch_tree.  Fill
// the per-branch vectors (parents before children), then link(): it derives
// depths and child lists from the parents and points the record at
// everything.  Moving keeps the record valid (vectors keep their buffers).
#pragma once

#include <arbor/branch_tree.h>

#include <string>
#include <vector>

namespace arbor {

struct BranchTreeArrays {
    // The host's measure columns, in this order (ARBOR_MEASURE_*).
    static constexpr uint32_t kMeasureCount = 5;
    static const char *const kMeasureIds[kMeasureCount];

    std::vector<int32_t> parent; // [n]: -1 for the root, parent[b] < b
    std::vector<arbor_extremum_kind> kind;
    std::vector<int64_t> saddle_vertex, extremum_vertex;
    std::vector<double> saddle_value, extremum_value;
    std::vector<double> saddle_position, extremum_position; // [3n]
    std::vector<double> measures, relative;                 // [n * kMeasureCount], row per branch
    std::vector<double> importance;                         // [n] or empty (no simplifier)
    // Columns beyond the topology's (the host may add measures, branch_tree.h):
    // ids, and [n] values of each.
    std::vector<std::string> extra_ids;
    std::vector<std::vector<double>> extra;
    // The volume's stored -> physical mapping (ABI 1.4 fields of the record).
    double value_scale = 1.0, value_offset = 0.0;
    std::string value_unit;

    // Every vector sized for n branches (values zero, kinds maximum, root's parent -1).
    void resize(std::size_t n);
    const arbor_branch_tree &link();
    const arbor_branch_tree &record() const { return record_; }

private:
    std::vector<uint32_t> depth_, child_offsets_, children_;
    std::vector<double> all_measures_, all_relative_; // with the extra columns
    std::vector<const char *> ids_;
    std::vector<char> unit_; // value_unit with its NUL: a heap buffer, kept by moves
    arbor_branch_tree record_{};
};

} // namespace arbor
