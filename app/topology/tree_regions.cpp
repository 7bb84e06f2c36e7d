#include "tree_regions.hpp"

#include "branch_decomposition.hpp"

#include "core/parallel_ranges.hpp"
#include "core/voxel_type.hpp"

#include <stdexcept>
#include <vector>

namespace arbor::topology {

namespace {

// Interior voxels of every arc (nodes excluded) added to count/sum, for
// the voxels [begin, end); returns their value sum.
template <class T>
double sum_arcs(const T *values, uint32_t begin, uint32_t end, const uint32_t *vertex_arc,
                const HugeVector<uint64_t> &is_node, uint32_t *count, double *sum)
{
    double total = 0.0;
    for (uint32_t v = begin; v < end; ++v) {
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

// Whether sums of the values are exact in doubles whatever their order (8-
// and 16-bit integers: under 2^53 for up to 2^32 voxels), so that splitting
// the voxels between cores cannot change a measure.
bool sums_exactly(arbor_voxel_type type)
{
    return is_integer_voxel_type(type) && arbor_voxel_size(type) <= 2;
}

} // namespace

TreeRegions::TreeRegions(const ContourTree &tree, const FieldView &field) : tree_(tree)
{
    node_value_.resize(tree.node_count());
    dispatch_voxel_type(field.type, [&](auto t) {
        using T = decltype(t);
        const T *values = static_cast<const T *>(field.values);
        for (std::size_t x = 0; x < tree.node_count(); ++x)
            node_value_[x] = static_cast<double>(values[tree.node_vertex[x]]);
    });
    root_at_minimum();
    sum_subtrees(field);
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
        // Split between the cores where that leaves the sums exact: each
        // part but the first counts into arrays of its own, added after.
        const std::size_t least = sums_exactly(field.type) ? kSplitSumsVoxels : std::max<std::size_t>(field.count, 1);
        const std::size_t parts = range_parts(field.count, least);
        std::vector<HugeVector<uint32_t>> counts(parts);
        std::vector<HugeVector<double>> sums(parts);
        std::vector<double> totals(parts, 0.0);
        for (std::size_t p = 1; p < parts; ++p) {
            counts[p].assign(tree_.arc_count(), 0);
            sums[p].assign(tree_.arc_count(), 0.0);
        }
        dispatch_voxel_type(field.type, [&](auto t) {
            using T = decltype(t);
            const T *values = static_cast<const T *>(field.values);
            for_ranges(field.count, least, [&](std::size_t begin, std::size_t end, std::size_t p) {
                totals[p] = sum_arcs(values, static_cast<uint32_t>(begin), static_cast<uint32_t>(end),
                                     tree_.vertex_arc.data(), is_node, p == 0 ? below_count_.data() : counts[p].data(),
                                     p == 0 ? below_sum_.data() : sums[p].data());
            });
        });
        total_sum_ = 0.0;
        for (std::size_t p = 0; p < parts; ++p)
            total_sum_ += totals[p];
        for (std::size_t p = 1; p < parts; ++p)
            for (std::size_t a = 0; a < tree_.arc_count(); ++a) {
                below_count_[a] += counts[p][a];
                below_sum_[a] += sums[p][a];
            }
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
