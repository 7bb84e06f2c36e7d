#include "tree_regions.hpp"

#include "branch_decomposition.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <limits>
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
    below_ = root_at(0);
    above_ = root_at(static_cast<uint32_t>(nodes - 1));
}

uint32_t TreeRegions::far_end(uint32_t arc, uint32_t from) const
{
    return tree_.arc_lo[arc] == from ? tree_.arc_hi[arc] : tree_.arc_lo[arc];
}

TreeRegions::Rooted TreeRegions::root_at(uint32_t root) const
{
    const std::size_t nodes = tree_.node_count();
    Rooted r;
    r.parent_arc.assign(nodes, kNoArc);
    r.count.assign(nodes, 0.0);
    r.sum.assign(nodes, 0.0);
    // Preorder by an explicit stack (trees of noisy data are deep).
    std::vector<uint32_t> preorder;
    preorder.reserve(nodes);
    std::vector<uint32_t> stack{root};
    std::vector<uint8_t> seen(nodes, 0);
    seen[root] = 1;
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
            r.parent_arc[y] = a;
            stack.push_back(y);
        }
    }
    if (preorder.size() != nodes)
        throw std::logic_error("contour tree is not connected");
    // Children before parents: each node adds itself, then hands its sums on.
    for (auto it = preorder.rbegin(); it != preorder.rend(); ++it) {
        const uint32_t x = *it;
        r.count[x] += 1.0;
        r.sum[x] += node_value_[x];
        const uint32_t a = r.parent_arc[x];
        if (a == kNoArc)
            continue;
        const uint32_t p = far_end(a, x);
        r.count[p] += r.count[x] + arc_count_[a];
        r.sum[p] += r.sum[x] + arc_sum_[a];
    }
    return r;
}

RegionSums TreeRegions::measure(const Side &s) const
{
    const bool down_side = tree_.arc_hi[s.arc] == s.saddle; // the region lies below the saddle
    const Rooted &rooted = down_side ? below_ : above_;
    const uint32_t far = far_end(s.arc, s.saddle);
    RegionSums r;
    if (rooted.parent_arc[far] != s.arc) {
        r.toward_root = true;
        return r;
    }
    r.count = 1.0 + arc_count_[s.arc] + rooted.count[far];
    r.sum = node_value_[s.saddle] + arc_sum_[s.arc] + rooted.sum[far];
    return r;
}

} // namespace arbor::topology
