#include "tree_regions.hpp"

#include "branch_decomposition.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <stdexcept>

namespace arbor::topology {

namespace {

template <class T>
void sum_arcs(const T *values, uint32_t n, const uint32_t *vertex_arc, const std::vector<uint64_t> &is_node,
              std::vector<double> &count, std::vector<double> &sum)
{
    for (uint32_t v = 0; v < n; ++v) {
        if ((is_node[v >> 6] >> (v & 63)) & 1u)
            continue;
        const uint32_t a = vertex_arc[v];
        count[a] += 1.0;
        sum[a] += static_cast<double>(values[v]);
    }
}

} // namespace

TreeRegions::TreeRegions(const ContourTree &tree, const FieldView &field) : tree_(tree)
{
    const std::size_t nodes = tree.node_count();
    node_value_.resize(nodes);
    for (std::size_t x = 0; x < nodes; ++x)
        node_value_[x] = field.value(tree.node_vertex[x]);
    arc_count_.assign(tree.arc_count(), 0.0);
    arc_sum_.assign(tree.arc_count(), 0.0);
    if (tree.arc_count() > 0) {
        std::vector<uint64_t> is_node((field.count + 63) / 64, 0);
        for (uint32_t v : tree.node_vertex)
            is_node[v >> 6] |= uint64_t{1} << (v & 63);
        dispatch_voxel_type(field.type, [&](auto t) {
            using T = decltype(t);
            sum_arcs(static_cast<const T *>(field.values), field.count, tree.vertex_arc.data(), is_node,
                     arc_count_, arc_sum_);
        });
    }
    total_count_ = static_cast<double>(nodes);
    total_sum_ = 0.0;
    for (double v : node_value_)
        total_sum_ += v;
    for (std::size_t a = 0; a < tree.arc_count(); ++a) {
        total_count_ += arc_count_[a];
        total_sum_ += arc_sum_[a];
    }
    root_at_minimum();
}

uint32_t TreeRegions::far_end(uint32_t arc, uint32_t from) const
{
    return tree_.arc_lo[arc] == from ? tree_.arc_hi[arc] : tree_.arc_lo[arc];
}

void TreeRegions::root_at_minimum()
{
    const std::size_t nodes = tree_.node_count();
    parent_arc_.assign(nodes, kNoArc);
    sub_count_.assign(nodes, 0.0);
    sub_sum_.assign(nodes, 0.0);
    // Preorder by an explicit stack (trees of noisy data are deep).
    std::vector<uint32_t> &preorder = preorder_;
    preorder.reserve(nodes);
    depth_.assign(nodes, 0);
    std::vector<uint32_t> stack{0};
    std::vector<uint8_t> seen(nodes, 0);
    seen[0] = 1;
    while (!stack.empty()) {
        const uint32_t x = stack.back();
        stack.pop_back();
        preorder.push_back(x);
        for (uint32_t i = tree_.node_arc_offsets[x]; i < tree_.node_arc_offsets[x + 1]; ++i) {
            const uint32_t a = tree_.node_arcs[i];
            const uint32_t y = far_end(a, x);
            if (seen[y])
                continue;
            seen[y] = 1;
            parent_arc_[y] = a;
            depth_[y] = depth_[x] + 1;
            stack.push_back(y);
        }
    }
    if (preorder.size() != nodes)
        throw std::logic_error("contour tree is not connected");
    // Children before parents: each node adds itself, then hands its sums on.
    for (auto it = preorder.rbegin(); it != preorder.rend(); ++it) {
        const uint32_t x = *it;
        sub_count_[x] += 1.0;
        sub_sum_[x] += node_value_[x];
        const uint32_t a = parent_arc_[x];
        if (a == kNoArc)
            continue;
        const uint32_t p = far_end(a, x);
        sub_count_[p] += sub_count_[x] + arc_count_[a];
        sub_sum_[p] += sub_sum_[x] + arc_sum_[a];
    }
}

RegionSums TreeRegions::measure(const Side &s) const
{
    const uint32_t far = far_end(s.arc, s.saddle);
    RegionSums r;
    if (parent_arc_[far] == s.arc) {
        // The arc leads away from the root: the region is the subtree beyond.
        r.count = 1.0 + arc_count_[s.arc] + sub_count_[far];
        r.sum = node_value_[s.saddle] + arc_sum_[s.arc] + sub_sum_[far];
    } else {
        // The arc leads to the root: everything but the saddle's subtree,
        // plus the saddle.
        r.count = total_count_ - sub_count_[s.saddle] + 1.0;
        r.sum = total_sum_ - sub_sum_[s.saddle] + node_value_[s.saddle];
    }
    return r;
}

} // namespace arbor::topology
