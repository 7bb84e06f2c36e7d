#include "merge_tree.hpp"

#include <vector>

namespace arbor::topology {

namespace {

// Root of x's component, halving the path on the way.
inline uint32_t find_root(uint32_t *uf, uint32_t x)
{
    while (uf[x] != x) {
        uf[x] = uf[uf[x]];
        x = uf[x];
    }
    return x;
}

template <bool Join>
MergeTree sweep(const GridNeighbors &grid, const UninitializedBuffer<uint32_t> &order_buffer,
                const ProgressFn &progress, const SweepScratch &scratch)
{
    const uint32_t n = static_cast<uint32_t>(order_buffer.size());
    MergeTree tree;
    tree.parent = UninitializedBuffer<uint32_t>(n);
    tree.children = UninitializedBuffer<uint8_t>(n);
    // Union-find by rank (balanced, so finds stay short), plus the newest
    // vertex of each component, which the next merge attaches to.
    const uint32_t *order = order_buffer.data();
    uint32_t *parent = tree.parent.data();
    uint8_t *children = tree.children.data();
    uint32_t *u = scratch.uf;
    uint32_t *newest = scratch.top;
    uint8_t *h = scratch.height;
    // A neighbour is lower (join) or higher (split) than the current vertex
    // exactly when the sweep has already passed it: one bit per vertex says
    // so.  The bits fit in cache where the values would not, which matters
    // because consecutive vertices of the sweep lie anywhere in the volume.
    std::vector<uint64_t> swept((n + 63) / 64, 0);
    uint64_t *seen = swept.data();
    constexpr uint32_t kProgressStep = 1u << 20;
    // The sweep order is known ahead: fetch the union-find entries around
    // the vertex a few steps on, so that the misses of consecutive vertices
    // overlap.
    constexpr uint32_t kAhead = 16;
    const int64_t row = grid.nx(), plane = grid.nx() * grid.ny();
    const auto prefetch = [&](uint32_t at) {
        const int64_t w = order[Join ? at : n - 1 - at];
        for (const int64_t p : {w - plane, w, w + plane})
            for (const int64_t r : {p - row, p, p + row})
                if (r >= 0 && r < static_cast<int64_t>(n))
                    __builtin_prefetch(u + r);
    };

    for (uint32_t step = 0; step < n; ++step) {
        if (step + kAhead < n)
            prefetch(step + kAhead);
        const uint32_t v = order[Join ? step : n - 1 - step];
        uint32_t roots[14];
        int count = 0;
        grid.for_each(v, [&](int64_t neighbor) {
            const uint32_t w = static_cast<uint32_t>(neighbor);
            if (!((seen[w >> 6] >> (w & 63)) & 1u))
                return;
            const uint32_t c = find_root(u, w);
            for (int i = 0; i < count; ++i)
                if (roots[i] == c)
                    return;
            roots[count++] = c;
        });
        seen[v >> 6] |= uint64_t{1} << (v & 63);
        children[v] = static_cast<uint8_t>(count);
        uint32_t root = v;
        if (count == 0) {
            u[v] = v;
            h[v] = 0;
        } else {
            root = roots[0];
            parent[newest[root]] = v;
            for (int i = 1; i < count; ++i) {
                const uint32_t c = roots[i];
                parent[newest[c]] = v;
                if (h[c] > h[root]) {
                    u[root] = c;
                    root = c;
                } else {
                    u[c] = root;
                    if (h[c] == h[root])
                        ++h[root];
                }
            }
            u[v] = root;
        }
        newest[root] = v;
        if (progress && (step & (kProgressStep - 1)) == kProgressStep - 1)
            progress(static_cast<double>(step) / n);
    }
    if (n > 0)
        parent[order[Join ? n - 1 : 0]] = kNoVertex;
    return tree;
}

template <bool Join>
MergeTree sweep_any(const GridNeighbors &grid, arbor_voxel_type type, const void *values,
                    const UninitializedBuffer<uint32_t> &order, const ProgressFn &progress,
                    const SweepScratch *scratch)
{
    UninitializedBuffer<uint32_t> uf, top;
    UninitializedBuffer<uint8_t> height;
    SweepScratch own{};
    if (!scratch) {
        uf = UninitializedBuffer<uint32_t>(order.size());
        top = UninitializedBuffer<uint32_t>(order.size());
        height = UninitializedBuffer<uint8_t>(order.size());
        own = {uf.data(), top.data(), height.data()};
        scratch = &own;
    }
    (void)type;
    (void)values;
    return sweep<Join>(grid, order, progress, *scratch);
}

} // namespace

MergeTree compute_join_tree(const GridNeighbors &grid, arbor_voxel_type type, const void *values,
                            const UninitializedBuffer<uint32_t> &order, const ProgressFn &progress,
                            const SweepScratch *scratch)
{
    return sweep_any<true>(grid, type, values, order, progress, scratch);
}

MergeTree compute_split_tree(const GridNeighbors &grid, arbor_voxel_type type, const void *values,
                             const UninitializedBuffer<uint32_t> &order, const ProgressFn &progress,
                             const SweepScratch *scratch)
{
    return sweep_any<false>(grid, type, values, order, progress, scratch);
}

} // namespace arbor::topology
