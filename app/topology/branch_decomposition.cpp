#include "branch_decomposition.hpp"

#include "tree_regions.hpp"

#include "core/voxel_type.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace arbor::topology {

const char *measure_id(int measure)
{
    switch (measure) {
    case kPersistence: return "persistence";
    case kVolume: return "volume";
    case kVolumeMm3: return "volume-mm3";
    case kHypervolume: return "hypervolume";
    case kRelativeHypervolume: return "relative-hypervolume";
    default: return "?";
    }
}

double FieldView::value(uint32_t vertex) const
{
    return dispatch_voxel_type(type, [&](auto t) {
        using T = decltype(t);
        return static_cast<double>(static_cast<const T *>(values)[vertex]);
    });
}

ImportanceFn persistence_importance()
{
    return [](const std::vector<BranchMeasures> &rows, std::vector<double> &out) {
        for (std::size_t i = 0; i < rows.size(); ++i)
            out[i] = rows[i].relative[kPersistence];
    };
}

namespace {

// |det| of the direction matrix times the spacings: mm^3 per voxel.
double voxel_volume(const Geometry &g)
{
    const auto &d = g.direction;
    const double det = d[0] * (d[4] * d[8] - d[5] * d[7]) - d[1] * (d[3] * d[8] - d[5] * d[6]) +
                       d[2] * (d[3] * d[7] - d[4] * d[6]);
    return std::fabs(det) * g.spacing[0] * g.spacing[1] * g.spacing[2];
}

// Union-find over contour-tree nodes whose roots carry the representative
// extremum of their component.
class Components {
public:
    explicit Components(std::size_t n) : parent_(n), rep_(n) {}
    // Nodes enter by make(); a component's root is its most recent node.
    void make(uint32_t x)
    {
        parent_[x] = x;
        rep_[x] = x;
    }
    uint32_t find(uint32_t x)
    {
        while (parent_[x] != x) {
            parent_[x] = parent_[parent_[x]];
            x = parent_[x];
        }
        return x;
    }
    uint32_t rep(uint32_t root) const { return rep_[root]; }
    // Joins a into root b, which keeps representative `rep`.
    void join(uint32_t a, uint32_t b, uint32_t rep)
    {
        parent_[a] = b;
        rep_[b] = rep;
    }

private:
    HugeVector<uint32_t> parent_, rep_;
};

class Decomposer {
public:
    Decomposer(const ContourTree &tree, const FieldView &field, const ImportanceFn &importance)
        : tree_(tree), importance_(importance), regions_(tree, field)
    {
        gmin_ = 0;
        gmax_ = static_cast<uint32_t>(tree.node_count() - 1);
        f_min_ = regions_.node_value(gmin_);
        f_max_ = regions_.node_value(gmax_);
        mm3_ = voxel_volume(*field.geometry);
        root_.absolute[kPersistence] = f_max_ - f_min_;
        root_.absolute[kVolume] = regions_.total_count();
        root_.absolute[kVolumeMm3] = regions_.total_count() * mm3_;
        root_.absolute[kHypervolume] = regions_.total_sum() - regions_.total_count() * f_min_;
        root_.absolute[kRelativeHypervolume] = root_.absolute[kHypervolume];
        for (int m = 0; m < kMeasureCount; ++m)
            root_.relative[m] = root_.absolute[m] > 0 ? 1.0 : 0.0;
        root_.kind = BranchKind::Root;
        root_.saddle_value = f_min_;
        root_.extremum_value = f_max_;
    }

    BranchDecomposition run(const ProgressFn &progress)
    {
        // One branch per extremum but the global minimum, which the root
        // shares with the global maximum.
        std::size_t extrema = 0;
        for (std::size_t x = 0; x < tree_.node_count(); ++x)
            extrema += (tree_.node_up[x] == 0) + (tree_.node_down[x] == 0);
        out_.branches.reserve(extrema);
        Branch root;
        root.extremum_node = gmax_;
        root.saddle_node = gmin_;
        root.importance = std::numeric_limits<double>::infinity();
        root.measures = root_.absolute;
        root.saddle_value = f_min_;
        root.extremum_value = f_max_;
        out_.branches.push_back(root);
        {
            Components comp(tree_.node_count());
            sweep(/*join=*/true, comp, progress, 0.0);
            sweep(/*join=*/false, comp, progress, 0.35);
        }
        if (progress)
            progress(0.7);
        regions_.release_sums();
        assemble();
        return std::move(out_);
    }

private:
    uint32_t far_end(uint32_t arc, uint32_t from) const { return regions_.far_node(arc, from); }

    BranchMeasures measures_of(uint32_t saddle, uint32_t arc, uint32_t extremum, bool basin) const
    {
        const RegionSums r = regions_.measure({saddle, arc});
        const double fs = regions_.node_value(saddle);
        BranchMeasures m;
        m.absolute[kPersistence] = std::fabs(fs - regions_.node_value(extremum));
        m.absolute[kVolume] = r.count;
        m.absolute[kVolumeMm3] = r.count * mm3_;
        m.absolute[kHypervolume] = r.sum - r.count * f_min_;
        // The volume between the function and the saddle level: sum over the
        // region of f - f(saddle) for a peak, f(saddle) - f for a basin.  It is
        // the sum of |f - f(saddle)| whenever the region lies on one side of
        // its saddle level; a pit inside a peak's region (a bump inside a
        // basin's) counts against it.  Exact |.| sums would need the value
        // distribution of every region, out of reach in O(1) per branch.
        m.absolute[kRelativeHypervolume] = std::max(0.0, basin ? r.count * fs - r.sum : r.sum - r.count * fs);
        for (int i = 0; i < kMeasureCount; ++i)
            m.relative[i] = root_.absolute[i] > 0 ? m.absolute[i] / root_.absolute[i] : 0.0;
        m.kind = basin ? BranchKind::Minimum : BranchKind::Maximum;
        m.saddle_value = fs;
        m.extremum_value = regions_.node_value(extremum);
        return m;
    }

    // The elder rule on the join tree (join: nodes upwards, components of
    // sublevel sets) or on the split tree (downwards, superlevel sets), both
    // rebuilt from the contour tree by union-find over its nodes.  Where two
    // or more components meet at a node, each is a candidate branch: the
    // component's representative extremum and the region beyond the node on
    // the component's arc.  The most important continues (the global extremum
    // of the sweep always does; equal importance: the older extremum), the
    // others end at the node.
    // Progress (and so cancellation) is polled every 64 Ki nodes, from
    // `from` to `from` + 0.35.
    void sweep(bool join, Components &comp, const ProgressFn &progress, double from)
    {
        const std::size_t nodes = tree_.node_count();
        const uint32_t forced = join ? gmin_ : gmax_;
        std::vector<uint32_t> arcs, roots;
        std::vector<BranchMeasures> rows;
        std::vector<double> values;
        for (std::size_t step = 0; step < nodes; ++step) {
            if (progress && (step & 0xffff) == 0)
                progress(from + 0.35 * static_cast<double>(step) / static_cast<double>(nodes));
            const uint32_t x = static_cast<uint32_t>(join ? step : nodes - 1 - step);
            comp.make(x);
            arcs.clear();
            roots.clear();
            for (uint32_t k = tree_.node_arc_offsets[x]; k < tree_.node_arc_offsets[x + 1]; ++k) {
                const uint32_t a = tree_.node_arcs[k];
                if ((join ? tree_.arc_hi[a] : tree_.arc_lo[a]) != x)
                    continue; // not an arc from a node swept before x
                const uint32_t r = comp.find(far_end(a, x));
                if (std::find(roots.begin(), roots.end(), r) != roots.end())
                    continue;
                arcs.push_back(a);
                roots.push_back(r);
            }
            if (roots.empty())
                continue; // an extremum of the sweep starts its component
            std::size_t best = 0;
            if (roots.size() > 1) {
                rows.clear();
                for (std::size_t i = 0; i < roots.size(); ++i) {
                    const uint32_t rep = comp.rep(roots[i]);
                    rows.push_back(rep == forced ? root_ : measures_of(x, arcs[i], rep, join));
                }
                values.assign(rows.size(), 0.0);
                importance_(rows, values);
                for (std::size_t i = 0; i < roots.size(); ++i) {
                    if (comp.rep(roots[i]) != forced && (!std::isfinite(values[i]) || values[i] < 0.0))
                        throw std::invalid_argument(
                            "the importance function returned " + std::to_string(values[i]) +
                            " for a branch (persistence " + std::to_string(rows[i].absolute[kPersistence]) +
                            ", volume " + std::to_string(rows[i].absolute[kVolume]) +
                            "); importance must be a finite number >= 0");
                    if (i != best && continues_instead(comp.rep(roots[i]), comp.rep(roots[best]), values[i],
                                                       values[best], forced, join))
                        best = i;
                }
                for (std::size_t i = 0; i < roots.size(); ++i) {
                    if (i == best)
                        continue;
                    Branch b;
                    b.kind = join ? BranchKind::Minimum : BranchKind::Maximum;
                    b.extremum_node = comp.rep(roots[i]);
                    b.saddle_node = x;
                    b.importance = values[i];
                    b.measures = rows[i].absolute;
                    b.saddle_value = rows[i].saddle_value;
                    b.extremum_value = rows[i].extremum_value;
                    out_.branches.push_back(b);
                }
            }
            const uint32_t survivor = comp.rep(roots[best]);
            for (uint32_t r : roots)
                comp.join(r, x, survivor);
        }
    }

    // True when candidate a should continue instead of b.
    static bool continues_instead(uint32_t a, uint32_t b, double ia, double ib, uint32_t forced, bool join)
    {
        if (b == forced)
            return false;
        if (a == forced)
            return true;
        if (ia != ib)
            return ia > ib;
        // Equal importance: the older extremum continues (node indices follow
        // the simulated order: lower is older for minima, higher for maxima).
        return join ? a < b : a > b;
    }

    // Orders the branches breadth first from the root and fills in parents,
    // depths, children and the owner of every arc and node.
    void assemble()
    {
        HugeVector<Branch> &branches = out_.branches;
        const std::size_t total = branches.size();
        out_.global_min = f_min_;
        out_.global_max = f_max_;
        out_.arc_branch.assign(tree_.arc_count(), kNoArc);
        // Provisional ids: the sweeps' order.
        HugeVector<uint32_t> parent = assign_arcs(out_.arc_branch);

        // Breadth first from the root, so parents come first and siblings
        // are consecutive.
        HugeVector<uint32_t> final_id(total, 0);
        {
            HugeVector<uint32_t> kid_offsets(total + 1, 0), kids(total - 1);
            for (uint32_t b = 1; b < total; ++b)
                ++kid_offsets[parent[b] + 1];
            for (std::size_t b = 0; b < total; ++b)
                kid_offsets[b + 1] += kid_offsets[b];
            {
                HugeVector<uint32_t> fill(kid_offsets.begin(), kid_offsets.end() - 1);
                for (uint32_t b = 1; b < total; ++b)
                    kids[fill[parent[b]]++] = b;
            }
            HugeVector<uint32_t> order;
            order.reserve(total);
            order.push_back(0);
            for (std::size_t k = 0; k < order.size(); ++k)
                for (uint32_t i = kid_offsets[order[k]]; i < kid_offsets[order[k] + 1]; ++i)
                    order.push_back(kids[i]);
            if (order.size() != total)
                throw std::logic_error("branch hierarchy is not a tree");
            for (uint32_t k = 0; k < total; ++k)
                final_id[order[k]] = k;
        }
        for (uint32_t b = 1; b < total; ++b)
            branches[b].parent = static_cast<int32_t>(final_id[parent[b]]);
        parent = {};
        for (uint32_t &id : out_.arc_branch)
            id = final_id[id];
        // Into the final order in place, one cycle of the permutation at a time.
        for (uint32_t i = 0; i < total; ++i)
            while (final_id[i] != i) {
                const uint32_t j = final_id[i];
                std::swap(branches[i], branches[j]);
                std::swap(final_id[i], final_id[j]);
            }
        final_id = {};
        out_.child_offsets.assign(total + 1, 0);
        out_.child_offsets[0] = 1;
        for (uint32_t k = 1; k < total; ++k) {
            const auto p = static_cast<uint32_t>(branches[k].parent);
            branches[k].depth = branches[p].depth + 1;
            ++out_.child_offsets[p + 1];
        }
        for (std::size_t b = 0; b < total; ++b)
            out_.child_offsets[b + 1] += out_.child_offsets[b];
        // A node goes with the arc rootwards of it (towards the global
        // minimum): for a saddle, the branch that goes on through it.
        const HugeVector<uint32_t> &up = regions_.parent_arc();
        out_.node_branch.resize(tree_.node_count());
        for (uint32_t x = 0; x < tree_.node_count(); ++x)
            out_.node_branch[x] = up[x] == kNoArc ? 0 : out_.arc_branch[up[x]];
    }

    // Which branch owns each arc (provisional ids), and each branch's parent.
    //
    // The root owns the tree path from the global minimum to the global
    // maximum; every other branch, in decreasing importance, the arcs of the
    // tree path from its extremum to its saddle that no more important branch
    // owns.  Where the pairs form a branch decomposition (every volume of the
    // shared data) these paths are disjoint monotone paths and this is exactly
    // that decomposition.  In the rare trees where no monotone decomposition
    // realises the pairs (1 x 1 x n strips, the 3 x 2 plane 5 1 4 / 2 3 0 whose
    // global extrema no monotone path joins), paths overlap and the more
    // important branch keeps the shared arcs; pairs and measures stay the
    // elder rule's.
    //
    // A branch's parent owns the arc just rootwards of the branch's rootmost
    // arc, so the rootmost depth falls along every parent chain: a tree.
    HugeVector<uint32_t> assign_arcs(HugeVector<uint32_t> &owner) const
    {
        const HugeVector<Branch> &branches = out_.branches;
        const HugeVector<uint32_t> &up = regions_.parent_arc();
        const HugeVector<uint32_t> &depth = regions_.depth();
        const std::size_t total = branches.size();
        const auto arc_depth = [&](uint32_t a) { return std::max(depth[tree_.arc_lo[a]], depth[tree_.arc_hi[a]]); };
        HugeVector<uint32_t> top_arc(total, kNoArc), first_arc(total, kNoArc);
        const auto claim = [&](uint32_t a, uint32_t id) {
            if (owner[a] != kNoArc)
                return;
            owner[a] = id;
            if (top_arc[id] == kNoArc || arc_depth(a) < arc_depth(top_arc[id]))
                top_arc[id] = a;
        };
        const auto claim_path = [&](uint32_t from, uint32_t to, uint32_t id) {
            while (from != to) {
                const bool from_side = depth[from] >= depth[to];
                uint32_t &deeper = from_side ? from : to;
                const uint32_t a = up[deeper];
                if (from_side && first_arc[id] == kNoArc)
                    first_arc[id] = a;
                claim(a, id);
                deeper = far_end(a, deeper);
            }
        };
        claim_path(gmax_, gmin_, 0);
        {
            // Most important first; equal importance: in the sweeps' order.
            HugeVector<std::pair<double, uint32_t>> by_importance(total - 1);
            for (uint32_t id = 1; id < total; ++id)
                by_importance[id - 1] = {branches[id].importance, id};
            std::sort(by_importance.begin(), by_importance.end(), [](const auto &a, const auto &b) {
                return a.first != b.first ? a.first > b.first : a.second < b.second;
            });
            for (const auto &[importance, id] : by_importance)
                claim_path(branches[id].extremum_node, branches[id].saddle_node, id);
        }
        // Arcs on no pair's path go with the arc rootwards of them.
        for (uint32_t x : regions_.preorder()) {
            const uint32_t a = up[x];
            if (a == kNoArc || owner[a] != kNoArc)
                continue;
            const uint32_t rootwards = up[far_end(a, x)];
            claim(a, rootwards == kNoArc ? 0 : owner[rootwards]);
        }
        HugeVector<uint32_t> parent(total, 0);
        for (uint32_t id = 1; id < total; ++id) {
            const uint32_t a = top_arc[id];
            if (a == kNoArc) {
                // Every arc of its path went to more important branches (an
                // extremum that is also a saddle, like the inner extrema of a
                // strip): it hangs off the owner of its first arc and, owning
                // nothing, is nobody's parent.
                parent[id] = first_arc[id] == kNoArc ? 0 : owner[first_arc[id]];
                continue;
            }
            const uint32_t near = depth[tree_.arc_lo[a]] < depth[tree_.arc_hi[a]] ? tree_.arc_lo[a] : tree_.arc_hi[a];
            parent[id] = up[near] == kNoArc ? 0 : owner[up[near]];
        }
        return parent;
    }

    const ContourTree &tree_;
    const ImportanceFn &importance_;
    TreeRegions regions_;
    uint32_t gmin_ = 0, gmax_ = 0;
    double f_min_ = 0, f_max_ = 0, mm3_ = 1;
    BranchMeasures root_;
    BranchDecomposition out_;
};

} // namespace

BranchDecomposition decompose_branches(const ContourTree &tree, const FieldView &field,
                                       const ImportanceFn &importance, const ProgressFn &progress)
{
    if (tree.node_count() == 0)
        throw std::invalid_argument("cannot decompose an empty contour tree");
    return Decomposer(tree, field, importance).run(progress);
}

} // namespace arbor::topology
