#include "tree_regions.hpp"

#include "branch_decomposition.hpp"

#include "core/voxel_type.hpp"

#include <stdexcept>

namespace arbor::topology {

namespace {

// Interior voxels of every arc (nodes excluded) into count/sum, and the sum
// over all voxels.
template <class T>
double sum_arcs(const T *values, uint32_t n, const uint32_t *vertex_arc, const HugeVector<uint64_t> &is_node,
                uint32_t *count, double *sum)
{
    double total = 0.0;
    for (uint32_t v = 0; v < n; ++v) {
        const double f = static_cast<double>(values[v]);
        total += f;
        if ((is_node[v >> 6] >> (v & 63)) & 1u)
            continue;
        const uint32_t a = vertex_arc[v];
        ++count[a];
        sum[a] += f;
    }
    return total;
}

} // namespace

TreeRegions::TreeRegions(const ContourTree &tree, const FieldView &field) : tree_(tree), field_(field)
{
    root_at_minimum();
    sum_subtrees(field);
}

double TreeRegions::node_value(uint32_t node) const
{
    return field_.value(tree_.node_vertex[node]);
}

void TreeRegions::root_at_minimum()
{
    const std::size_t nodes = tree_.node_count();
    parent_arc_.assign(nodes, kNoArc);
    depth_.assign(nodes, 0);
    preorder_.reserve(nodes);
    // Preorder by an explicit stack (trees of noisy data are deep).  A node
    // is reached once its parent arc is set; the root has none.
    HugeVector<uint32_t> stack{0};
    while (!stack.empty()) {
        const uint32_t x = stack.back();
        stack.pop_back();
        preorder_.push_back(x);
        for (uint32_t i = tree_.node_arc_offsets[x]; i < tree_.node_arc_offsets[x + 1]; ++i) {
            const uint32_t a = tree_.node_arcs[i];
            const uint32_t y = far_node(a, x);
            if (y == 0 || parent_arc_[y] != kNoArc)
                continue;
            parent_arc_[y] = a;
            depth_[y] = depth_[x] + 1;
            stack.push_back(y);
        }
    }
    if (preorder_.size() != nodes)
        throw std::logic_error("contour tree is not connected");
}

void TreeRegions::sum_subtrees(const FieldView &field)
{
    below_count_.assign(tree_.arc_count(), 0);
    below_sum_.assign(tree_.arc_count(), 0.0);
    total_count_ = field.count;
    if (tree_.arc_count() == 0) {
        total_sum_ = field.value(0);
        return;
    }
    {
        HugeVector<uint64_t> is_node((field.count + 63) / 64, 0);
        for (uint32_t v : tree_.node_vertex)
            is_node[v >> 6] |= uint64_t{1} << (v & 63);
        total_sum_ = dispatch_voxel_type(field.type, [&](auto t) {
            using T = decltype(t);
            return sum_arcs(static_cast<const T *>(field.values), field.count, tree_.vertex_arc.data(), is_node,
                            below_count_.data(), below_sum_.data());
        });
    }
    // Children before parents: each node adds itself to its parent arc, which
    // then hands its sums on to the parent's parent arc.
    for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
        const uint32_t x = *it;
        const uint32_t a = parent_arc_[x];
        if (a == kNoArc)
            continue;
        below_count_[a] += 1;
        below_sum_[a] += node_value(x);
        const uint32_t up = parent_arc_[far_node(a, x)];
        if (up != kNoArc) {
            below_count_[up] += below_count_[a];
            below_sum_[up] += below_sum_[a];
        }
    }
}

void TreeRegions::release_sums()
{
    below_count_ = {};
    below_sum_ = {};
}

RegionSums TreeRegions::measure(const Side &s) const
{
    RegionSums r;
    if (parent_arc_[far_node(s.arc, s.saddle)] == s.arc) {
        // The arc leads away from the root: the saddle plus what lies below
        // the arc.
        r.count = 1.0 + below_count_[s.arc];
        r.sum = node_value(s.saddle) + below_sum_[s.arc];
        return r;
    }
    // The arc leads to the root: everything but what hangs below the saddle.
    r.count = total_count_;
    r.sum = total_sum_;
    for (uint32_t i = tree_.node_arc_offsets[s.saddle]; i < tree_.node_arc_offsets[s.saddle + 1]; ++i) {
        const uint32_t b = tree_.node_arcs[i];
        if (b == s.arc)
            continue;
        r.count -= below_count_[b];
        r.sum -= below_sum_[b];
    }
    return r;
}

} // namespace arbor::topology
