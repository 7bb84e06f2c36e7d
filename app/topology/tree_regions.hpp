// tree_regions.hpp - voxel counts and value sums over the regions of a
// contour tree, from its augmentation: the voxels of every arc, then subtree
// sums in the tree rooted at the global minimum (for regions below saddles)
// or at the global maximum (for regions above them).
//
// The region of a side of a saddle s is the saddle plus everything beyond the
// arc that leaves s on that side: the region enclosed by the contour through
// s on that arc.  Rooting the tree at the global minimum puts every region
// that can hang below a saddle away from the root, and rooting it at the global
// maximum does the same for regions above; so a region is always a subtree.
#pragma once

#include "contour_tree.hpp"

#include <cstdint>
#include <vector>

namespace arbor::topology {

struct FieldView;

struct RegionSums {
    double count = 0.0;
    double sum = 0.0; // of the stored values
    // The side leads to the global extremum the tree is rooted at.  Its region
    // is not a subtree: it holds the rest of the volume (such a side only
    // arises where simulation of simplicity splits a flat plateau).
    bool toward_root = false;
};

class TreeRegions {
public:
    TreeRegions(const ContourTree &tree, const FieldView &field);

    double node_value(uint32_t node) const { return node_value_[node]; }
    // Interior voxels of an arc (its nodes excluded) and their value sum.
    double arc_count(uint32_t arc) const { return arc_count_[arc]; }
    double arc_sum(uint32_t arc) const { return arc_sum_[arc]; }
    double total_count() const { return total_count_; }
    double total_sum() const { return total_sum_; }

    // A side of a saddle: the saddle node and the arc that leaves it there.
    struct Side {
        uint32_t saddle;
        uint32_t arc;
    };

    // Voxel count and value sum over the region of a side, in O(1) from the
    // subtree sums.  Sides below their saddle (arc_hi == saddle) are measured
    // in the tree rooted at the global minimum, sides above in the one rooted
    // at the global maximum; a side that leads to that root is flagged.
    RegionSums measure(const Side &side) const;

private:
    struct Rooted {
        std::vector<uint32_t> parent_arc;         // per node; kNoArc for the root
        std::vector<double> count, sum; // subtree sums per node
    };
    Rooted root_at(uint32_t root) const;
    uint32_t far_end(uint32_t arc, uint32_t from) const;

    const ContourTree &tree_;
    std::vector<double> node_value_;
    std::vector<double> arc_count_, arc_sum_; // interior vertices only
    double total_count_ = 0.0, total_sum_ = 0.0;
    Rooted below_, above_; // rooted at the global minimum / maximum
};

} // namespace arbor::topology
