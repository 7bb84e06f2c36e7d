#include "merge_tree.hpp"

#include "link_components.hpp"

#include <algorithm>
#include <vector>

namespace arbor::topology {

namespace {

// Union-find over components: link, newest vertex (its rank), union-by-rank
// height.  One entry per component (a leaf of the tree), created as the sweep
// finds it.
struct Components {
    std::vector<uint32_t> link;
    std::vector<uint32_t> newest;
    std::vector<uint8_t> height;

    uint32_t create(uint32_t rank)
    {
        const uint32_t c = static_cast<uint32_t>(link.size());
        link.push_back(c);
        newest.push_back(rank);
        height.push_back(0);
        return c;
    }

    // Root of c's component, halving the path on the way.
    uint32_t find(uint32_t c)
    {
        uint32_t *l = link.data();
        while (l[c] != c) {
            l[c] = l[l[c]];
            c = l[c];
        }
        return c;
    }

    // Root of c's component without changing the links: for look-ahead.
    uint32_t peek(uint32_t c) const
    {
        const uint32_t *l = link.data();
        while (l[c] != c)
            c = l[c];
        return c;
    }

    // Unites the roots a and b; returns the new root.
    uint32_t unite(uint32_t a, uint32_t b)
    {
        if (height[b] > height[a])
            std::swap(a, b);
        link[b] = a;
        if (height[a] == height[b])
            ++height[a];
        return a;
    }
};

template <bool Join>
void sweep(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state, uint32_t *component,
           const ProgressFn &progress)
{
    const uint32_t n = order.size();
    const std::vector<LinkComponents> &link = link_components_table();
    Components components;
    // A neighbour is below the current vertex (above, for the split tree)
    // exactly when the sweep has passed it: one bit per vertex says so.  The
    // bits fit in cache where per-vertex words would not; which neighbours'
    // components are needed then follows from the bits alone (one per piece
    // of the lower link), so a step reads one or two component words, mostly
    // in the current vertex's own cache line.
    std::vector<uint64_t> swept((n + 63) / 64, 0);
    uint64_t *seen = swept.data();
    constexpr uint32_t kProgressStep = 1u << 20;
    // The sweep order is known ahead: fetch what a vertex a few steps on
    // will read, so that the misses of consecutive vertices overlap.  Two
    // stages: the swept bits of its neighbourhood (and its own state) 32
    // steps ahead; 16 steps ahead those bits are in cache and say which
    // neighbours' component words it will read (one per piece of its lower
    // link, usually in other rows and planes), so those are fetched too.
    constexpr uint32_t kAhead = 16;
    static_assert(2 * kAhead <= OrderPieces::kLookahead);
    const int64_t row = grid.nx(), plane = grid.nx() * grid.ny();
    const auto lower_link = [&](uint32_t v) {
        uint32_t below = 0;
        grid.for_each_indexed(v, [&](std::size_t i, int64_t neighbor) {
            const uint64_t w = static_cast<uint64_t>(neighbor);
            below |= static_cast<uint32_t>((seen[w >> 6] >> (w & 63)) & 1u) << i;
        });
        return below;
    };
    const auto prefetch_bits = [&](int64_t w) {
        __builtin_prefetch(&component[w], 1);
        for (const int64_t p : {w - plane, w, w + plane})
            for (const int64_t r : {p - row, p, p + row})
                if (r >= 0 && r < static_cast<int64_t>(n))
                    __builtin_prefetch(seen + (r >> 6));
    };
    // The lower links seen 16 steps ahead, kept for the third stage: 8
    // steps ahead the pieces' component words are in cache and name the
    // components the vertex will join, whose newest vertices it will write
    // (a store to a line not in cache stalls every store behind it).  Links
    // and components may change in between; a stale guess costs one fetch.
    constexpr uint32_t kNear = 8;
    uint32_t ahead_below[kAhead];
    const auto prefetch_components = [&](uint32_t w, uint32_t at) {
        const uint32_t below = lower_link(w);
        ahead_below[at % kAhead] = below;
        const LinkComponents &pieces = link[below];
        for (int p = 0; p < pieces.count; ++p)
            __builtin_prefetch(&component[w + grid.offset(pieces.first[p])]);
    };
    const auto prefetch_newest = [&](uint32_t w, uint32_t at) {
        const LinkComponents &pieces = link[ahead_below[at % kAhead]];
        for (int p = 0; p < pieces.count; ++p) {
            const uint32_t c = component[w + grid.offset(pieces.first[p])];
            if (c < components.link.size())
                __builtin_prefetch(&state[components.newest[components.peek(c)]], 1);
        }
    };

    order.walk(!Join, [&](const OrderPiece &piece, uint32_t first) {
        for (uint32_t i = 0; i < piece.count; ++i) {
            const uint32_t step = first + i;
            if (step + 2 * kAhead < n)
                prefetch_bits(piece[i + 2 * kAhead]);
            if (step + kAhead < n)
                prefetch_components(piece[i + kAhead], step + kAhead);
            if (step + kNear < n && step + kNear >= kAhead)
                prefetch_newest(piece[i + kNear], step + kNear);
            const uint32_t v = piece[i];
            const uint32_t rank = Join ? step : n - 1 - step;
            const uint32_t below = lower_link(v);
            seen[v >> 6] |= uint64_t{1} << (v & 63);
            const LinkComponents &pieces = link[below];
            uint32_t roots[6];
            int count = 0;
            for (int p = 0; p < pieces.count; ++p) {
                const uint32_t r = components.find(component[v + grid.offset(pieces.first[p])]);
                bool known = false;
                for (int i = 0; i < count; ++i)
                    known |= roots[i] == r;
                if (!known)
                    roots[count++] = r;
            }
            (Join ? state[rank].jt_deg : state[rank].st_deg) = static_cast<uint8_t>(count);
            uint32_t root;
            if (count == 0) {
                root = components.create(rank);
            } else {
                root = roots[0];
                for (int i = 0; i < count; ++i) {
                    MergeVertex &joined = state[components.newest[roots[i]]];
                    (Join ? joined.jt_up : joined.st_down) = rank;
                    if (i > 0)
                        root = components.unite(root, roots[i]);
                }
                components.newest[root] = rank;
            }
            component[v] = root;
            if (progress && (step & (kProgressStep - 1)) == kProgressStep - 1)
                progress(static_cast<double>(step) / n);
        }
    });
    if (n > 0) { // the last vertex swept: the root of the tree
        MergeVertex &last = state[Join ? n - 1 : 0];
        (Join ? last.jt_up : last.st_down) = kNoVertex;
    }
}

} // namespace

void compute_join_tree(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state,
                       uint32_t *component, const ProgressFn &progress)
{
    sweep<true>(grid, order, state, component, progress);
}

void compute_split_tree(const GridNeighbors &grid, const OrderPieces &order, MergeVertex *state,
                        uint32_t *component, const ProgressFn &progress)
{
    sweep<false>(grid, order, state, component, progress);
}

} // namespace arbor::topology
