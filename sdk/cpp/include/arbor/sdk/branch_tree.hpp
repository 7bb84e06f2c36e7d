// arbor/sdk/branch_tree.hpp - a checked, read-only C++ view of an
// arbor_branch_tree for depictor and transfer-function plugins.
#pragma once

#include <arbor/branch_tree.h>

#include "error.hpp"

#include <cmath>
#include <cstring>
#include <span>
#include <string>

namespace arbor::sdk {

class BranchTreeView {
public:
    // Fails with ARBOR_ERROR_INVALID_ARGUMENT for a NULL or malformed record
    // (missing arrays, parents not before children, bad child lists).
    explicit BranchTreeView(const arbor_branch_tree *tree) : t_(tree)
    {
        if (!t_)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree is NULL");
        if (t_->struct_size < ARBOR_MIN_SIZE(arbor_branch_tree))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree: struct_size too small");
        if (t_->branch_count == 0)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree has no branches");
        if (!t_->parent || !t_->depth || !t_->child_offsets || (!t_->children && t_->branch_count > 1) ||
            !t_->extremum_kind || !t_->saddle_value || !t_->extremum_value || !t_->saddle_vertex ||
            !t_->extremum_vertex || (t_->measure_count > 0 && (!t_->measure_ids || !t_->measures ||
                                                               !t_->relative_measures)))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree has NULL arrays");
        if (t_->parent[0] != -1 || t_->child_offsets[0] != 0 ||
            t_->child_offsets[t_->branch_count] != t_->branch_count - 1)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree: malformed root or child offsets");
        for (uint32_t b = 1; b < t_->branch_count; ++b)
            if (t_->parent[b] < 0 || static_cast<uint32_t>(t_->parent[b]) >= b)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree: parent of branch " + std::to_string(b) +
                                                       " does not come before it");
        for (uint32_t b = 0; b < t_->branch_count; ++b)
            if (t_->child_offsets[b + 1] < t_->child_offsets[b])
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree: child offsets decrease");
        for (uint32_t i = 0; i + 1 < t_->branch_count; ++i)
            if (t_->children[i] >= t_->branch_count)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch tree: child index out of range");
    }

    const arbor_branch_tree &record() const { return *t_; }
    uint32_t size() const { return t_->branch_count; }
    int32_t parent(uint32_t b) const { return t_->parent[b]; }
    uint32_t depth(uint32_t b) const { return t_->depth[b]; }
    std::span<const uint32_t> children(uint32_t b) const
    {
        return {t_->children + t_->child_offsets[b], t_->child_offsets[b + 1] - t_->child_offsets[b]};
    }
    bool is_minimum(uint32_t b) const { return t_->extremum_kind[b] == ARBOR_EXTREMUM_MINIMUM; }
    double saddle_value(uint32_t b) const { return t_->saddle_value[b]; }
    double extremum_value(uint32_t b) const { return t_->extremum_value[b]; }
    // True when a is b or a descendant of b (parents come first, so the walk
    // up from a stops as soon as it passes b).
    bool within(uint32_t a, uint32_t b) const
    {
        while (a > b)
            a = static_cast<uint32_t>(t_->parent[a]);
        return a == b;
    }

    // Column of measure `id`, or -1.
    int column(const char *id) const
    {
        for (uint32_t c = 0; c < t_->measure_count; ++c)
            if (t_->measure_ids[c] && std::strcmp(t_->measure_ids[c], id) == 0)
                return static_cast<int>(c);
        return -1;
    }
    // Like column() but fails with ARBOR_ERROR_NOT_FOUND naming the measure.
    uint32_t require_column(const char *id) const
    {
        const int c = column(id);
        if (c < 0)
            fail(ARBOR_ERROR_NOT_FOUND, std::string("the branch tree has no measure '") + id + "'");
        return static_cast<uint32_t>(c);
    }
    double measure(uint32_t b, uint32_t column) const { return t_->measures[b * t_->measure_count + column]; }
    double relative(uint32_t b, uint32_t column) const
    {
        return t_->relative_measures[b * t_->measure_count + column];
    }

private:
    const arbor_branch_tree *t_;
};

} // namespace arbor::sdk
