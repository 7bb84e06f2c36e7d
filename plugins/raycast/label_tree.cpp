#include "label_tree.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::raycast {

void LabelTree::assign(const arbor_label_map *map)
{
    nodes_.clear();
    if (!map || !ARBOR_HAS_FIELD(arbor_label_map, map->struct_size, saddle_value) || !map->parent ||
        !map->saddle_value || map->label_count == 0)
        return;
    std::vector<Node> nodes(map->label_count);
    for (uint32_t l = 0; l < map->label_count; ++l) {
        const int32_t p = map->parent[l];
        const bool rooted = l == 0 ? p == -1 : p >= 0 && static_cast<uint32_t>(p) < l;
        if (!rooted || !std::isfinite(map->saddle_value[l]))
            return; // not a tree we can walk: nearest-voxel labels
        nodes[l] = {p, l == 0 ? 0u : nodes[static_cast<uint32_t>(p)].depth + 1,
                    static_cast<float>(map->saddle_value[l])};
    }
    nodes_ = std::move(nodes);
}

uint32_t LabelTree::close_paths(uint32_t *labels, uint32_t count, uint32_t capacity) const
{
    if (count < 2 || nodes_.empty())
        return count;
    for (uint32_t n = 0; n < count; ++n)
        if (labels[n] >= nodes_.size())
            return count; // labels the tree does not know resolve to nothing new
    // The common ancestor of them all.
    uint32_t top = labels[0];
    for (uint32_t n = 1; n < count; ++n) {
        uint32_t a = top, b = labels[n];
        while (a != b) {
            if (nodes_[a].depth >= nodes_[b].depth)
                a = static_cast<uint32_t>(nodes_[a].parent);
            else
                b = static_cast<uint32_t>(nodes_[b].parent);
        }
        top = a;
    }
    const uint32_t given = count;
    for (uint32_t n = 0; n < given; ++n)
        for (uint32_t l = labels[n]; l != top;) {
            l = static_cast<uint32_t>(nodes_[l].parent);
            if (std::find(labels, labels + count, l) != labels + count)
                continue;
            if (count == capacity)
                return capacity + 1;
            labels[count++] = l;
        }
    return count;
}

} // namespace arbor::raycast
