// tree_regions.hpp - voxel counts and value sums over the regions of a
// contour tree, from its augmentation: the voxels of every arc, then subtree
// sums in the tree rooted at the global minimum.
//
// The region of a side of a saddle s is the saddle plus everything beyond the
// arc that leaves s on that side: the region enclosed by the contour through
// s on that arc.  It is a subtree when the arc points away from the root, and
// the rest of the tree (plus s) when it points towards it.
#pragma once

#include "contour_tree.hpp"

#include <cstdint>
#include <vector>

namespace arbor::topology {

struct FieldView;

struct RegionSums {
    double count = 0.0;
    double sum = 0.0; // of the stored values
};

class TreeRegions {
public:
    TreeRegions(const ContourTree &tree, const FieldView &field);

    double node_value(uint32_t node) const { return node_value_[node]; }
    // Interior voxels of an arc (its nodes excluded) and their value sum.
    double arc_count(uint32_t arc) const { return arc_count_[arc]; }
    double arc_sum(uint32_t arc) const { return arc_sum_[arc]; }
    // The tree rooted at the global minimum (node 0): each node's arc towards
    // the root (kNoArc for the root), its depth, and a preorder.
    const std::vector<uint32_t> &parent_arc() const { return parent_arc_; }
    const std::vector<uint32_t> &depth() const { return depth_; }
    const std::vector<uint32_t> &preorder() const { return preorder_; }
    uint32_t far_node(uint32_t arc, uint32_t from) const { return far_end(arc, from); }
    double total_count() const { return total_count_; }
    double total_sum() const { return total_sum_; }

    // A side of a saddle: the saddle node and the arc that leaves it there.
    struct Side {
        uint32_t saddle;
        uint32_t arc;
    };

    // Voxel count and value sum over the region of a side, in O(1) from the
    // subtree sums.
    RegionSums measure(const Side &side) const;

private:
    uint32_t far_end(uint32_t arc, uint32_t from) const;
    void root_at_minimum();

    const ContourTree &tree_;
    std::vector<double> node_value_;
    std::vector<double> arc_count_, arc_sum_; // interior vertices only
    double total_count_ = 0.0, total_sum_ = 0.0;
    // Rooted at the global minimum: parent arc, depth and subtree sums per
    // node, and a preorder.
    std::vector<uint32_t> parent_arc_, depth_, preorder_;
    std::vector<double> sub_count_, sub_sum_;
};

} // namespace arbor::topology
