// tree_regions.hpp - voxel counts and value sums over the regions of a
// contour tree, from its augmentation: the voxels of every arc, then sums
// over the subtrees of the tree rooted at the global minimum.
//
// The region of a side of a saddle s is the saddle plus everything beyond the
// arc that leaves s on that side: the region enclosed by the contour through
// s on that arc.  It is a subtree when the arc points away from the root, and
// the rest of the tree (plus s) when it points towards it.
#pragma once

#include "contour_tree.hpp"
#include "../core/huge_pages.hpp"

#include <cstddef>
#include <cstdint>

namespace arbor::topology {

struct FieldView;

// The least voxels one core sums when the sums are split between cores (8-
// and 16-bit values, whose sums are exact in any order).
inline constexpr std::size_t kSplitSumsVoxels = std::size_t{1} << 18;

struct RegionSums {
    double count = 0.0;
    double sum = 0.0; // of the stored values
};

class TreeRegions {
public:
    TreeRegions(const ContourTree &tree, const FieldView &field);

    double node_value(uint32_t node) const { return node_value_[node]; }
    // The tree rooted at the global minimum (node 0): each node's arc towards
    // the root (kNoArc for the root), its depth, and a preorder.
    const HugeVector<uint32_t> &parent_arc() const { return parent_arc_; }
    const HugeVector<uint32_t> &depth() const { return depth_; }
    const HugeVector<uint32_t> &preorder() const { return preorder_; }
    uint32_t far_node(uint32_t arc, uint32_t from) const
    {
        return tree_.arc_lo[arc] == from ? tree_.arc_hi[arc] : tree_.arc_lo[arc];
    }
    double total_count() const { return total_count_; }
    double total_sum() const { return total_sum_; }

    // A side of a saddle: the saddle node and the arc that leaves it there.
    struct Side {
        uint32_t saddle;
        uint32_t arc;
    };

    // Voxel count and value sum over the region of a side, from the subtree
    // sums in O(degree of the saddle).  Not after release_sums().
    RegionSums measure(const Side &side) const;
    // Frees the sums once every region is measured (the rooted tree stays).
    void release_sums();

private:
    void root_at_minimum();
    void sum_subtrees(const FieldView &field);

    const ContourTree &tree_;
    double total_count_ = 0.0, total_sum_ = 0.0;
    // The value at every node, read once: the decomposition asks for the
    // values of saddles and extrema tens of millions of times.
    HugeVector<double> node_value_;
    HugeVector<uint32_t> parent_arc_, depth_, preorder_;
    // Per arc, for its end away from the root: the voxels of that node's
    // subtree plus the arc's interior, and their value sum.
    HugeVector<uint32_t> below_count_;
    HugeVector<double> below_sum_;
};

} // namespace arbor::topology
