// label_tree.hpp - how the labels of a label map nest, and the label a
// sample takes from its interpolated value: topology-controlled volume
// rendering (Weber, Dillard, Carr, Pascucci, Hamann, IEEE TVCG 2007).
//
// The region of a branch is bounded by the isosurface at its saddle value.
// A sample in a cell whose corners carry different labels lies, in the
// contour tree, on the path between the places of a corner below its value
// and a corner above it.  Walking that path from both ends towards their
// common ancestor, the deeper end first (it cannot be the ancestor), a
// branch whose stretch of the path crosses the sample's value holds the
// sample: the low end's branch when its saddle is at or above the value
// (its stretch rises from the corner's value to the saddle), the high
// end's when its saddle is at or below it.  Where the ends meet, the
// branch they meet in holds it.  So a boundary between structures is a
// trilinear isosurface, not a wall of voxel cubes, whatever the kind of
// either branch (peaks and basins alike).
#pragma once

#include <arbor/branch_tree.h>

#include <cstdint>
#include <vector>

namespace arbor::raycast {

class LabelTree {
public:
    // From the map's hierarchy (ABI 1.6); empty when the map has none, or
    // when it is not a tree rooted at label 0 whose parents come first.
    void assign(const arbor_label_map *map);
    void clear() { nodes_.clear(); }
    bool empty() const { return nodes_.empty(); }
    uint32_t size() const { return static_cast<uint32_t>(nodes_.size()); }

    // The label of a sample of `value` between a corner of label `low`
    // (value at most `value`) and one of label `high` (at least `value`).
    uint32_t resolve(uint32_t low, uint32_t high, float value) const
    {
        while (low != high) {
            const Node &l = nodes_[low], &h = nodes_[high];
            if (h.depth > l.depth) {
                if (h.saddle <= value)
                    return high;
                high = static_cast<uint32_t>(h.parent);
            } else {
                if (l.saddle >= value)
                    return low;
                low = static_cast<uint32_t>(l.parent);
            }
        }
        return low;
    }

    // Every label on the paths between `labels[0..count)` and their common
    // ancestor, added to the list (each once): the labels a sample among
    // them can resolve to.  Stops adding at `capacity`; returns the count
    // (capacity + 1 when more would not fit).
    uint32_t close_paths(uint32_t *labels, uint32_t count, uint32_t capacity) const;

    int32_t parent(uint32_t label) const { return nodes_[label].parent; }
    uint32_t depth(uint32_t label) const { return nodes_[label].depth; }
    float saddle(uint32_t label) const { return nodes_[label].saddle; }

private:
    struct Node {
        int32_t parent; // -1 for the root
        uint32_t depth; // the root 0
        float saddle;   // stored value, as the grid's values
    };
    std::vector<Node> nodes_;
};

} // namespace arbor::raycast
