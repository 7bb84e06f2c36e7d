#include "contour_tree.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace arbor::topology {

const char *node_kind_name(NodeKind kind)
{
    switch (kind) {
    case NodeKind::Minimum: return "minimum";
    case NodeKind::Maximum: return "maximum";
    case NodeKind::JoinSaddle: return "join-saddle";
    case NodeKind::SplitSaddle: return "split-saddle";
    case NodeKind::Saddle: return "saddle";
    case NodeKind::Lone: return "lone";
    }
    return "?";
}

int64_t ContourTree::node_of_vertex(uint32_t vertex) const
{
    const auto it = std::lower_bound(vertex_node.begin(), vertex_node.end(), std::make_pair(vertex, 0u));
    return it != vertex_node.end() && it->first == vertex ? static_cast<int64_t>(it->second) : -1;
}

namespace {

// Leaf pruning on the two augmented trees (Carr, Snoeyink, Axen).  A vertex is
// removed once it is a leaf of one tree with a single arc in the other: an
// upper leaf (no split-tree children, one join-tree child) hands its contour
// tree edge to its split-tree parent, a lower leaf symmetrically.  Removed
// vertices are skipped lazily by the finds, which compress the parent paths.
// Arcs are built on the fly: an edge leaving a regular vertex continues the
// arc that reached it; an edge leaving a node starts a new arc.
class LeafPruning {
public:
    LeafPruning(MergeTree &join, MergeTree &split, uint32_t n)
        : n_(n), jt_up_(join.parent.data()), jt_deg_(join.children.data()), st_down_(split.parent.data()),
          st_deg_(split.children.data()), removed_((n + 63) / 64, 0), label_(n), cnt_up_(n), cnt_down_(n)
    {
        std::fill(cnt_up_.data(), cnt_up_.data() + n, uint8_t{0});
        std::fill(cnt_down_.data(), cnt_down_.data() + n, uint8_t{0});
    }

    void run(const ProgressFn &progress)
    {
        std::vector<uint32_t> stack;
        for (uint32_t v = 0; v < n_; ++v)
            if (is_leaf(v))
                stack.push_back(v);
        uint32_t remaining = n_;
        const uint32_t step = std::max<uint32_t>(1, n_ / 64);
        while (!stack.empty() && remaining > 1) {
            const uint32_t v = stack.back();
            stack.pop_back();
            if (is_removed(v))
                continue;
            uint32_t w;
            if (st_deg_[v] == 0 && jt_deg_[v] == 1) {
                w = find(st_down_, v);
                emit(v, w, /*downward=*/true);
                --st_deg_[w];
            } else if (jt_deg_[v] == 0 && st_deg_[v] == 1) {
                w = find(jt_up_, v);
                emit(v, w, /*downward=*/false);
                --jt_deg_[w];
            } else {
                continue; // pushed while a leaf, no longer one
            }
            mark_removed(v);
            --remaining;
            if (is_leaf(w))
                stack.push_back(w);
            if (progress && (n_ - remaining) % step == 0)
                progress(static_cast<double>(n_ - remaining) / n_);
        }
        if (remaining != 1)
            throw std::logic_error("contour tree merge stopped with " + std::to_string(remaining) +
                                   " vertices left");
        for (uint32_t word = 0; word < removed_.size(); ++word)
            if (removed_[word] != ~uint64_t{0}) {
                for (uint32_t bit = 0; bit < 64; ++bit)
                    if (!((removed_[word] >> bit) & 1u)) {
                        last_ = word * 64 + bit;
                        break;
                    }
                break;
            }
        // The last vertex closes the arcs that reached it.
        if (cnt_up_[last_] + cnt_down_[last_] > 0)
            close_pending(last_);
    }

    UninitializedBuffer<uint32_t> &labels() { return label_; }
    const UninitializedBuffer<uint8_t> &up_counts() const { return cnt_up_; }
    const UninitializedBuffer<uint8_t> &down_counts() const { return cnt_down_; }
    struct Arc {
        uint32_t start, end;
        bool downward;
    };
    std::vector<Arc> &arcs() { return arcs_; }
    uint32_t last() const { return last_; }

private:
    bool is_removed(uint32_t v) const { return (removed_[v >> 6] >> (v & 63)) & 1u; }
    void mark_removed(uint32_t v) { removed_[v >> 6] |= uint64_t{1} << (v & 63); }

    bool is_leaf(uint32_t v) const
    {
        return (st_deg_[v] == 0 && jt_deg_[v] == 1) || (jt_deg_[v] == 0 && st_deg_[v] == 1);
    }

    // First vertex that is not removed along the parent links from v's
    // parent, compressing the path.
    uint32_t find(uint32_t *parent, uint32_t v)
    {
        uint32_t x = parent[v];
        uint32_t root = x;
        while (root != kNoVertex && is_removed(root))
            root = parent[root];
        if (root == kNoVertex)
            throw std::logic_error("contour tree merge found no vertex to attach to");
        while (x != root) {
            const uint32_t next = parent[x];
            parent[x] = root;
            x = next;
        }
        parent[v] = root;
        return root;
    }

    // The first arc that reached v is pending in label_[v]; it ends at v.
    void close_pending(uint32_t v) { arcs_[label_[v]].end = v; }

    void emit(uint32_t v, uint32_t w, bool downward)
    {
        const bool regular = downward ? (cnt_up_[v] == 1 && cnt_down_[v] == 0)
                                      : (cnt_down_[v] == 1 && cnt_up_[v] == 0);
        uint32_t arc;
        if (regular) {
            arc = label_[v]; // the arc that reached v goes on through it
        } else {
            if (cnt_up_[v] + cnt_down_[v] > 0)
                close_pending(v);
            arc = static_cast<uint32_t>(arcs_.size());
            arcs_.push_back({v, kNoVertex, downward});
        }
        label_[v] = arc;
        if (downward) {
            ++cnt_down_[v];
            ++cnt_up_[w];
        } else {
            ++cnt_up_[v];
            ++cnt_down_[w];
        }
        if (cnt_up_[w] + cnt_down_[w] == 1)
            label_[w] = arc; // pending: continues through w if w is regular
        else
            arcs_[arc].end = w; // w has two or more arcs: a node
    }

    uint32_t n_;
    uint32_t *jt_up_;
    uint8_t *jt_deg_;
    uint32_t *st_down_;
    uint8_t *st_deg_;
    std::vector<uint64_t> removed_;
    UninitializedBuffer<uint32_t> label_;
    UninitializedBuffer<uint8_t> cnt_up_, cnt_down_;
    std::vector<Arc> arcs_;
    uint32_t last_ = 0;
};

NodeKind kind_of(uint8_t up, uint8_t down)
{
    if (down == 0 && up == 0)
        return NodeKind::Lone;
    if (down == 0)
        return NodeKind::Minimum;
    if (up == 0)
        return NodeKind::Maximum;
    if (down >= 2 && up >= 2)
        return NodeKind::Saddle;
    return down >= 2 ? NodeKind::JoinSaddle : NodeKind::SplitSaddle;
}

} // namespace

ContourTree merge_contour_tree(MergeTree join, MergeTree split, arbor_voxel_type type, const void *values,
                               const ProgressFn &progress)
{
    const uint32_t n = static_cast<uint32_t>(join.parent.size());
    ContourTree ct;
    if (n == 0)
        return ct;
    LeafPruning pruning(join, split, n);
    pruning.run(progress);
    join.parent.release();
    split.parent.release();

    const auto &up = pruning.up_counts();
    const auto &down = pruning.down_counts();
    auto &arcs = pruning.arcs();

    // The merge may end on a regular vertex (one edge from each side): the
    // two arcs that meet there are one.
    std::vector<uint32_t> arc_alias(arcs.size());
    std::iota(arc_alias.begin(), arc_alias.end(), 0u);
    const uint32_t z = pruning.last();
    if (up[z] == 1 && down[z] == 1) {
        uint32_t a = kNoArc, b = kNoArc;
        for (uint32_t i = 0; i < arcs.size(); ++i)
            if (arcs[i].end == z)
                (a == kNoArc ? a : b) = i;
        // Arc a now runs from its start through z to b's start.
        arcs[a].end = arcs[b].start;
        arc_alias[b] = a;
        arcs[b].start = arcs[b].end = kNoVertex; // dropped
    }

    // Nodes: every vertex that is not regular, in simulated-value order.
    std::vector<uint32_t> nodes;
    for (uint32_t v = 0; v < n; ++v)
        if (!(up[v] == 1 && down[v] == 1))
            nodes.push_back(v);
    dispatch_voxel_type(type, [&](auto t) {
        using T = decltype(t);
        const T *f = static_cast<const T *>(values);
        std::sort(nodes.begin(), nodes.end(),
                  [f](uint32_t a, uint32_t b) { return f[a] < f[b] || (f[a] == f[b] && a < b); });
    });
    ct.node_vertex = nodes;
    ct.vertex_node.reserve(nodes.size());
    for (uint32_t i = 0; i < nodes.size(); ++i) {
        ct.node_up.push_back(up[nodes[i]]);
        ct.node_down.push_back(down[nodes[i]]);
        ct.node_kind.push_back(kind_of(up[nodes[i]], down[nodes[i]]));
        ct.vertex_node.emplace_back(nodes[i], i);
    }
    std::sort(ct.vertex_node.begin(), ct.vertex_node.end());

    // Arcs in node terms, compacted (a dropped arc maps to its alias).
    std::vector<uint32_t> compact(arcs.size(), kNoArc);
    for (uint32_t i = 0; i < arcs.size(); ++i) {
        if (arcs[i].start == kNoVertex)
            continue;
        const uint32_t s = static_cast<uint32_t>(ct.node_of_vertex(arcs[i].start));
        const uint32_t e = static_cast<uint32_t>(ct.node_of_vertex(arcs[i].end));
        compact[i] = static_cast<uint32_t>(ct.arc_lo.size());
        ct.arc_lo.push_back(std::min(s, e)); // node indices follow the value order
        ct.arc_hi.push_back(std::max(s, e));
    }
    for (uint32_t i = 0; i < arcs.size(); ++i)
        if (compact[i] == kNoArc)
            compact[i] = compact[arc_alias[i]];

    // Incidence lists.
    const std::size_t count = ct.node_vertex.size();
    ct.node_arc_offsets.assign(count + 1, 0);
    for (std::size_t a = 0; a < ct.arc_lo.size(); ++a) {
        ++ct.node_arc_offsets[ct.arc_lo[a] + 1];
        ++ct.node_arc_offsets[ct.arc_hi[a] + 1];
    }
    for (std::size_t v = 0; v < count; ++v)
        ct.node_arc_offsets[v + 1] += ct.node_arc_offsets[v];
    ct.node_arcs.resize(ct.node_arc_offsets[count]);
    std::vector<uint32_t> fill(ct.node_arc_offsets.begin(), ct.node_arc_offsets.end() - 1);
    for (std::size_t a = 0; a < ct.arc_lo.size(); ++a) {
        ct.node_arcs[fill[ct.arc_lo[a]]++] = static_cast<uint32_t>(a);
        ct.node_arcs[fill[ct.arc_hi[a]]++] = static_cast<uint32_t>(a);
    }

    // Augmentation: the labels are per vertex already; compact them in place.
    ct.vertex_arc = std::move(pruning.labels());
    if (arcs.empty()) {
        ct.vertex_arc[0] = kNoArc;
    } else {
        for (uint32_t v = 0; v < n; ++v)
            ct.vertex_arc[v] = compact[ct.vertex_arc[v]];
    }
    return ct;
}

} // namespace arbor::topology
