#include "contour_tree.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

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

HugeVector<uint32_t> arc_interior_voxels(const ContourTree &tree)
{
    HugeVector<uint32_t> count(tree.arc_count(), 0);
    const uint32_t *arc = tree.vertex_arc.data();
    for (std::size_t v = 0; v < tree.vertex_arc.size(); ++v)
        if (arc[v] != kNoArc)
            ++count[arc[v]];
    for (const uint32_t v : tree.node_vertex)
        if (arc[v] != kNoArc)
            --count[arc[v]];
    return count;
}

namespace {

constexpr uint8_t kRemoved = 0xff;

// Leaf pruning on the two augmented trees (Carr, Snoeyink, Axen).  A vertex is
// removed once it is a leaf of one tree with a single arc in the other: an
// upper leaf (no split-tree children, one join-tree child) hands its contour
// tree edge to its split-tree parent, a lower leaf symmetrically.  Removed
// vertices are skipped lazily by the finds, which compress the parent paths.
// Arcs are built on the fly: an edge leaving a regular vertex continues the
// arc that reached it; an edge leaving a node starts a new arc.  Vertices
// are ranks here, as in the state (merge_tree.hpp).
class LeafPruning {
public:
    // `arcs` bounds the number of arcs (the number of nodes).
    LeafPruning(MergeVertex *state, uint32_t *label, uint32_t n, std::size_t arcs) : n_(n), s_(state), label_(label)
    {
        arcs_.reserve(arcs);
    }

    // Prunes the trees to one vertex, and lists the ranks of the contour
    // tree's nodes in `nodes`, lowest first.
    void run(const ProgressFn &progress, HugeVector<uint32_t> &nodes)
    {
        uint32_t remaining = n_;
        const uint32_t step = std::max<uint32_t>(1, n_ / 64);
        uint32_t next_report = step;
        const auto report = [&] {
            if (progress && n_ - remaining >= next_report) {
                progress(static_cast<double>(n_ - remaining) / n_);
                next_report += step;
            }
        };
        // Passes over the ranks first, downwards then upwards: a vertex
        // whose edges above (below) were just removed is usually the next one
        // in the pass, and the state is indexed by rank, so a pass reads it
        // as a stream instead of chasing parent links.  Most vertices go in
        // the first passes; the stack finishes the rest.
        //
        // The first pass also lists the nodes, highest first: a vertex is a node when its degrees in
        // the contour tree (the split tree's up, the join tree's down) are
        // not both 1, and until it is removed, its degree left in each tree
        // plus the edges it has been handed on that side is that tree's
        // degree.  Passes remove only the vertex they visit, so no vertex is
        // removed before the first pass reaches it.
        constexpr int kPasses = 4;
        for (uint32_t r = n_; r-- > 0;) {
            const MergeVertex &sr = s_[r];
            if (sr.st_deg + sr.cnt_up != 1 || sr.jt_deg + sr.cnt_down != 1)
                nodes.push_back(r);
            if (remaining > 1 && remove_if_leaf(r, nullptr)) {
                --remaining;
                report();
            }
        }
        std::reverse(nodes.begin(), nodes.end());
        for (int pass = 1; pass < kPasses && remaining > 1; ++pass) {
            const uint32_t before = remaining;
            const bool downwards = pass % 2 == 0;
            for (uint32_t i = 0; i < n_ && remaining > 1; ++i)
                if (remove_if_leaf(downwards ? n_ - 1 - i : i, nullptr)) {
                    --remaining;
                    report();
                }
            if (remaining == before)
                break;
        }
        std::vector<uint32_t> stack;
        for (uint32_t r = 0; r < n_; ++r)
            if (s_[r].jt_deg != kRemoved && is_leaf(s_[r]))
                stack.push_back(r);
        // Leaves are taken a batch at a time and the vertices they will
        // attach to are prefetched first, so the cache misses of several
        // independent chains overlap instead of queueing one after another.
        constexpr std::size_t kBatch = 8;
        uint32_t batch[kBatch];
        while (!stack.empty() && remaining > 1) {
            std::size_t count = 0;
            while (count < kBatch && !stack.empty()) {
                const uint32_t r = stack.back();
                stack.pop_back();
                const MergeVertex &sr = s_[r];
                if (sr.jt_deg == kRemoved)
                    continue;
                __builtin_prefetch(&s_[sr.st_deg == 0 ? sr.st_down : sr.jt_up]);
                batch[count++] = r;
            }
            for (std::size_t i = 0; i < count && remaining > 1; ++i)
                if (remove_if_leaf(batch[i], &stack)) {
                    --remaining;
                    report();
                }
        }
        if (remaining != 1)
            throw std::logic_error("contour tree merge stopped with " + std::to_string(remaining) +
                                   " vertices left");
        for (uint32_t r = 0; r < n_; ++r)
            if (s_[r].jt_deg != kRemoved) {
                last_ = r;
                break;
            }
        // The last vertex closes the arcs that reached it.
        if (s_[last_].cnt_up + s_[last_].cnt_down > 0)
            close_pending(last_);
    }

    struct Arc {
        uint32_t start, end; // ranks
    };
    HugeVector<Arc> take_arcs() { return std::move(arcs_); }
    uint32_t last() const { return last_; }

private:
    // Removes v if it is a leaf now: hands its edge to the vertex it attaches
    // to, and pushes that vertex on `stack` (if given) when it becomes a leaf.
    bool remove_if_leaf(uint32_t v, std::vector<uint32_t> *stack)
    {
        MergeVertex &sv = s_[v];
        if (sv.jt_deg == kRemoved)
            return false;
        uint32_t w;
        if (sv.st_deg == 0 && sv.jt_deg == 1) {
            w = find(&MergeVertex::st_down, v);
            emit(v, w, /*downward=*/true);
            --s_[w].st_deg;
        } else if (sv.jt_deg == 0 && sv.st_deg == 1) {
            w = find(&MergeVertex::jt_up, v);
            emit(v, w, /*downward=*/false);
            --s_[w].jt_deg;
        } else {
            return false;
        }
        sv.jt_deg = kRemoved;
        if (stack && is_leaf(s_[w]))
            stack->push_back(w);
        return true;
    }

    static bool is_leaf(const MergeVertex &s)
    {
        return (s.st_deg == 0 && s.jt_deg == 1) || (s.jt_deg == 0 && s.st_deg == 1);
    }

    // First vertex that is not removed along the links from v's link,
    // compressing the path.
    uint32_t find(uint32_t MergeVertex::*link, uint32_t v)
    {
        uint32_t x = s_[v].*link;
        uint32_t root = x;
        while (root != kNoVertex && s_[root].jt_deg == kRemoved)
            root = s_[root].*link;
        if (root == kNoVertex)
            throw std::logic_error("contour tree merge found no vertex to attach to");
        while (x != root) {
            const uint32_t next = s_[x].*link;
            s_[x].*link = root;
            x = next;
        }
        s_[v].*link = root;
        return root;
    }

    // The first arc that reached v is pending in its label; it ends at v.
    void close_pending(uint32_t v) { arcs_[label_[v]].end = v; }

    void emit(uint32_t v, uint32_t w, bool downward)
    {
        MergeVertex &sv = s_[v];
        MergeVertex &sw = s_[w];
        const bool regular = downward ? (sv.cnt_up == 1 && sv.cnt_down == 0)
                                      : (sv.cnt_down == 1 && sv.cnt_up == 0);
        uint32_t arc;
        if (regular) {
            arc = label_[v]; // the arc that reached v goes on through it
        } else {
            if (sv.cnt_up + sv.cnt_down > 0)
                close_pending(v);
            arc = static_cast<uint32_t>(arcs_.size());
            arcs_.push_back({v, kNoVertex});
        }
        label_[v] = arc;
        if (downward) {
            ++sv.cnt_down;
            ++sw.cnt_up;
        } else {
            ++sv.cnt_up;
            ++sw.cnt_down;
        }
        if (sw.cnt_up + sw.cnt_down == 1)
            label_[w] = arc; // pending: continues through w if w is regular
        else
            arcs_[arc].end = w; // w has two or more arcs: a node
    }

    uint32_t n_;
    MergeVertex *s_;
    uint32_t *label_;
    HugeVector<Arc> arcs_;
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

ContourTree merge_contour_tree(UninitializedBuffer<MergeVertex> merge_state, UninitializedBuffer<uint32_t> labels,
                               OrderPieces order, const ProgressFn &progress)
{
    const uint32_t n = static_cast<uint32_t>(merge_state.size());
    ContourTree ct;
    if (n == 0)
        return ct;
    if (order.size() != n || labels.size() != n)
        throw std::invalid_argument("merge_contour_tree: the merge state, its labels and the vertex order differ in size");
    MergeVertex *state = merge_state.data();
    uint32_t *label = labels.data();
    // The contour tree's down-degrees are the join tree's, its up-degrees
    // the split tree's: its nodes are known before the merge.
    std::size_t node_count = 0;
    for (uint32_t r = 0; r < n; ++r) {
        MergeVertex &s = state[r];
        label[r] = 0;
        s.cnt_up = s.cnt_down = 0;
        node_count += s.jt_deg != 1 || s.st_deg != 1;
    }

    // The nodes' ranks, until the augmentation turns them into vertices.
    HugeVector<uint32_t> &node_rank = ct.node_vertex;
    node_rank.reserve(node_count);
    LeafPruning pruning(state, label, n, node_count);
    pruning.run(progress, node_rank);
    HugeVector<LeafPruning::Arc> arcs = pruning.take_arcs();

    // The merge may end on a regular vertex (one edge from each side): the
    // two arcs that meet there are one.
    const uint32_t z = pruning.last();
    uint32_t dropped = kNoArc, kept = kNoArc;
    if (state[z].cnt_up == 1 && state[z].cnt_down == 1) {
        for (uint32_t i = 0; i < arcs.size(); ++i)
            if (arcs[i].end == z)
                (kept == kNoArc ? kept : dropped) = i;
        // Arc `kept` now runs from its start through z to the other's start.
        arcs[kept].end = arcs[dropped].start;
        arcs[dropped].start = arcs[dropped].end = kNoVertex;
    }

    // Nodes, in the order of their values: every vertex that is not
    // regular.
    if (ct.node_vertex.size() != node_count)
        throw std::logic_error("contour tree merge found " + std::to_string(ct.node_vertex.size()) +
                               " nodes where the merge trees have " + std::to_string(node_count));
    ct.node_up.resize(node_count);
    ct.node_down.resize(node_count);
    ct.node_kind.resize(node_count);
    for (std::size_t i = 0; i < node_count; ++i) {
        const MergeVertex &sv = state[node_rank[i]];
        ct.node_up[i] = sv.cnt_up;
        ct.node_down[i] = sv.cnt_down;
        ct.node_kind[i] = kind_of(sv.cnt_up, sv.cnt_down);
    }

    // Arcs are numbered as the merge made them, less the dropped one, which
    // is the one it joined.
    const auto compact = [dropped, kept](uint32_t arc) {
        if (dropped == kNoArc || arc < dropped)
            return arc;
        if (arc == dropped)
            arc = kept;
        return arc > dropped ? arc - 1 : arc;
    };

    // Augmentation: the arc of the vertex of rank r goes to its grid index
    // (from the order), in place of the state, which is no longer read: the
    // state's first third holds vertex_arc, and the rest of it is returned
    // to the system.  The peak stays the state's, no page is faulted in for
    // the segmentation, and the order goes before the tree's arcs are made.
    // On the way each node's rank becomes its vertex, and its label word,
    // read, names its index, for the arcs.
    char *arc_bytes = reinterpret_cast<char *>(state);
    constexpr uint32_t kAhead = 16;
    static_assert(kAhead <= OrderPieces::kLookahead);
    const bool lone = arcs.empty();
    std::size_t next_node = 0;
    order.walk(false, [&](const OrderPiece &piece, uint32_t first) {
        for (uint32_t i = 0; i < piece.count; ++i) {
            if (first + i + kAhead < n)
                __builtin_prefetch(arc_bytes + sizeof(uint32_t) * piece[i + kAhead], 1);
            const uint32_t r = first + i;
            const uint32_t arc = lone ? kNoArc : compact(label[r]);
            std::memcpy(arc_bytes + sizeof(uint32_t) * piece[i], &arc, sizeof arc);
            if (next_node < node_count && node_rank[next_node] == r) {
                label[r] = static_cast<uint32_t>(next_node);
                node_rank[next_node++] = piece[i];
            }
        }
    });
    if (next_node != node_count)
        throw std::logic_error("contour tree merge: the nodes' ranks are not in order");
    order.release();
    ct.vertex_arc = std::move(merge_state).shrink_to<uint32_t>(n);

    // Arcs in node terms.
    ct.arc_lo.reserve(arcs.size());
    ct.arc_hi.reserve(arcs.size());
    for (uint32_t i = 0; i < arcs.size(); ++i) {
        if (arcs[i].start == kNoVertex)
            continue;
        const uint32_t s = label[arcs[i].start], e = label[arcs[i].end];
        ct.arc_lo.push_back(std::min(s, e)); // node indices follow the value order
        ct.arc_hi.push_back(std::max(s, e));
    }
    arcs = {};
    labels.release();

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
    HugeVector<uint32_t> fill(ct.node_arc_offsets.begin(), ct.node_arc_offsets.end() - 1);
    for (std::size_t a = 0; a < ct.arc_lo.size(); ++a) {
        ct.node_arcs[fill[ct.arc_lo[a]]++] = static_cast<uint32_t>(a);
        ct.node_arcs[fill[ct.arc_hi[a]]++] = static_cast<uint32_t>(a);
    }
    return ct;
}

} // namespace arbor::topology
