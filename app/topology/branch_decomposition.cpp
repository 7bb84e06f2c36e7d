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

// A branch that ends at a saddle, before the branches are ordered.
struct EndingBranch {
    BranchKind kind;
    uint32_t extremum;
    uint32_t saddle;
    uint32_t arc; // the arc leaving the saddle on the branch's side
    BranchMeasures measures;
    double importance;
};

class Decomposer {
public:
    Decomposer(const ContourTree &tree, const FieldView &field, const ImportanceFn &importance)
        : tree_(tree), field_(field), importance_(importance), regions_(tree, field)
    {
        const std::size_t nodes = tree.node_count();
        gmin_ = 0;
        gmax_ = static_cast<uint32_t>(nodes - 1);
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
    }

    BranchDecomposition run(const ProgressFn &progress)
    {
        decide(/*downward=*/true);
        if (progress)
            progress(0.6);
        decide(/*downward=*/false);
        if (progress)
            progress(0.8);
        return assemble();
    }

private:
    uint32_t far_end(uint32_t arc, uint32_t from) const
    {
        return tree_.arc_lo[arc] == from ? tree_.arc_hi[arc] : tree_.arc_lo[arc];
    }

    BranchMeasures make_measures(double count, double sum, double saddle_value, double extremum_value,
                                 bool below) const
    {
        BranchMeasures m;
        m.absolute[kPersistence] = std::fabs(saddle_value - extremum_value);
        m.absolute[kVolume] = count;
        m.absolute[kVolumeMm3] = count * mm3_;
        m.absolute[kHypervolume] = sum - count * f_min_;
        // Height above (depth below) the saddle level, integrated over the
        // region: sum of |f - f(saddle)| whenever the region lies on one side
        // of its saddle's level; a pit inside a peak's region (a bump inside a
        // basin's) counts against it.
        m.absolute[kRelativeHypervolume] =
            std::max(0.0, below ? count * saddle_value - sum : sum - count * saddle_value);
        for (int i = 0; i < kMeasureCount; ++i)
            m.relative[i] = root_.absolute[i] > 0 ? m.absolute[i] / root_.absolute[i] : 0.0;
        return m;
    }

    // Measures of the candidate branch on side `arc` of `saddle`.
    BranchMeasures measures_of(uint32_t saddle, uint32_t arc, bool below, uint32_t extremum) const
    {
        const RegionSums r = regions_.measure({saddle, arc});
        if (r.toward_root) {
            // The side holds the rest of the volume: measure it as the whole.
            BranchMeasures m = root_;
            m.absolute[kPersistence] =
                std::fabs(regions_.node_value(saddle) - regions_.node_value(extremum));
            m.relative[kPersistence] =
                root_.absolute[kPersistence] > 0 ? m.absolute[kPersistence] / root_.absolute[kPersistence] : 0.0;
            return m;
        }
        return make_measures(r.count, r.sum, regions_.node_value(saddle), regions_.node_value(extremum), below);
    }

    // downward: decide at every node with two or more arcs below it, in
    // increasing order (the continuing path below each arc is known by then);
    // otherwise at every node with two or more arcs above, in decreasing order.
    void decide(bool downward)
    {
        const std::size_t nodes = tree_.node_count();
        std::vector<uint32_t> &cont = downward ? cont_down_ : cont_up_;
        std::vector<uint32_t> &rep = downward ? rep_min_ : rep_max_;
        cont.assign(nodes, kNoArc);
        rep.assign(nodes, 0);
        const uint32_t forced = downward ? gmin_ : gmax_;
        std::vector<uint32_t> arcs, reps;
        std::vector<BranchMeasures> rows;
        std::vector<double> values;
        for (std::size_t step = 0; step < nodes; ++step) {
            const uint32_t x = static_cast<uint32_t>(downward ? step : nodes - 1 - step);
            arcs.clear();
            for (uint32_t k = tree_.node_arc_offsets[x]; k < tree_.node_arc_offsets[x + 1]; ++k) {
                const uint32_t a = tree_.node_arcs[k];
                if ((downward ? tree_.arc_hi[a] : tree_.arc_lo[a]) == x)
                    arcs.push_back(a);
            }
            if (arcs.empty()) {
                rep[x] = x; // an extremum represents itself
                continue;
            }
            reps.clear();
            for (uint32_t a : arcs)
                reps.push_back(rep[far_end(a, x)]);
            if (arcs.size() == 1) {
                cont[x] = arcs[0];
                rep[x] = reps[0];
                continue;
            }
            // Candidates: every side; the one holding the global extremum of
            // this direction is forced to continue and needs no importance.
            rows.clear();
            for (std::size_t i = 0; i < arcs.size(); ++i)
                rows.push_back(reps[i] == forced ? root_ : measures_of(x, arcs[i], downward, reps[i]));
            values.assign(rows.size(), 0.0);
            importance_(rows, values);
            std::size_t best = 0;
            for (std::size_t i = 0; i < arcs.size(); ++i) {
                if (reps[i] != forced && (!std::isfinite(values[i]) || values[i] < 0.0))
                    throw std::invalid_argument(
                        "the importance function returned " + std::to_string(values[i]) +
                        " for a branch (persistence " + std::to_string(rows[i].absolute[kPersistence]) +
                        ", volume " + std::to_string(rows[i].absolute[kVolume]) +
                        "); importance must be a finite number >= 0");
                if (i == best)
                    continue;
                if (older_wins(reps[i], reps[best], values[i], values[best], forced, downward))
                    best = i;
            }
            cont[x] = arcs[best];
            rep[x] = reps[best];
            for (std::size_t i = 0; i < arcs.size(); ++i)
                if (i != best)
                    ending_.push_back({downward ? BranchKind::Minimum : BranchKind::Maximum, reps[i], x,
                                       arcs[i], rows[i], values[i]});
        }
    }

    // True when candidate a should continue instead of b.
    static bool older_wins(uint32_t a, uint32_t b, double ia, double ib, uint32_t forced, bool downward)
    {
        if (b == forced)
            return false;
        if (a == forced)
            return true;
        if (ia != ib)
            return ia > ib;
        // Equal importance: the older extremum continues (node indices follow
        // the simulated order: lower is older for minima, higher for maxima).
        return downward ? a < b : a > b;
    }

    BranchDecomposition assemble()
    {
        const std::size_t nodes = tree_.node_count();
        BranchDecomposition out;
        out.global_min = f_min_;
        out.global_max = f_max_;
        out.arc_branch.assign(tree_.arc_count(), kNoArc);
        out.node_branch.assign(nodes, kNoArc);

        // Provisional ids: 0 for the root, i + 1 for ending_[i].
        const auto walk = [&](uint32_t id, uint32_t from, uint32_t arc, bool downward) {
            uint32_t x = from;
            uint32_t a = arc;
            while (a != kNoArc) {
                if (out.arc_branch[a] != kNoArc)
                    throw std::logic_error("contour tree arc " + std::to_string(a) + " lies on two branches");
                out.arc_branch[a] = id;
                x = far_end(a, x);
                a = downward ? cont_down_[x] : cont_up_[x];
            }
        };
        if (tree_.arc_count() > 0)
            walk(0, gmin_, cont_up_[gmin_], /*downward=*/false);
        for (uint32_t i = 0; i < ending_.size(); ++i)
            walk(i + 1, ending_[i].saddle, ending_[i].arc, ending_[i].kind == BranchKind::Minimum);

        for (uint32_t a = 0; a < out.arc_branch.size(); ++a)
            if (out.arc_branch[a] == kNoArc)
                throw std::logic_error("contour tree arc " + std::to_string(a) + " lies on no branch");
        // Parent of a branch ending at s: the branch continuing through s.
        std::vector<int64_t> parent(ending_.size() + 1, -1);
        for (uint32_t i = 0; i < ending_.size(); ++i) {
            const uint32_t s = ending_[i].saddle;
            const uint32_t through = cont_down_[s] != kNoArc ? cont_down_[s] : cont_up_[s];
            parent[i + 1] = out.arc_branch[through];
        }
        // Order: breadth first from the root, so parents come first.
        std::vector<std::vector<uint32_t>> kids(ending_.size() + 1);
        for (uint32_t b = 1; b <= ending_.size(); ++b)
            kids[static_cast<std::size_t>(parent[b])].push_back(b);
        std::vector<uint32_t> order{0}, final_id(ending_.size() + 1, 0);
        for (std::size_t k = 0; k < order.size(); ++k)
            for (uint32_t c : kids[order[k]])
                order.push_back(c);
        if (order.size() != ending_.size() + 1)
            throw std::logic_error("branch hierarchy is not a tree");
        for (uint32_t k = 0; k < order.size(); ++k)
            final_id[order[k]] = k;

        out.branches.resize(order.size());
        for (uint32_t k = 0; k < order.size(); ++k) {
            const uint32_t b = order[k];
            Branch &br = out.branches[k];
            if (b == 0) {
                br.kind = BranchKind::Root;
                br.extremum_node = gmax_;
                br.saddle_node = gmin_;
                br.measures = root_;
                br.importance = std::numeric_limits<double>::infinity();
            } else {
                const EndingBranch &e = ending_[b - 1];
                br.kind = e.kind;
                br.extremum_node = e.extremum;
                br.saddle_node = e.saddle;
                br.measures = e.measures;
                br.importance = e.importance;
                br.parent = static_cast<int32_t>(final_id[static_cast<std::size_t>(parent[b])]);
                Branch &p = out.branches[static_cast<std::size_t>(br.parent)];
                br.depth = p.depth + 1;
                p.children.push_back(k);
            }
        }
        for (uint32_t &id : out.arc_branch)
            id = final_id[id];
        for (uint32_t x = 0; x < nodes; ++x) {
            const uint32_t a = cont_down_[x] != kNoArc ? cont_down_[x] : cont_up_[x];
            out.node_branch[x] = a == kNoArc ? 0 : out.arc_branch[a];
        }
        measure_regions(out);
        return out;
    }

    // Final measures from the hierarchy: a branch's region is its own arcs
    // and nodes, its descendants' regions, and its saddle.  Where every
    // branch region is one side of its saddle (always, except around flat
    // plateaus split by simulation of simplicity) this equals the side
    // measured for the decision.
    void measure_regions(BranchDecomposition &out) const
    {
        const std::size_t branches = out.branches.size();
        std::vector<double> count(branches, 0.0), sum(branches, 0.0);
        for (uint32_t a = 0; a < out.arc_branch.size(); ++a) {
            count[out.arc_branch[a]] += regions_.arc_count(a);
            sum[out.arc_branch[a]] += regions_.arc_sum(a);
        }
        for (uint32_t x = 0; x < out.node_branch.size(); ++x) {
            count[out.node_branch[x]] += 1.0;
            sum[out.node_branch[x]] += regions_.node_value(x);
        }
        for (std::size_t b = branches; b-- > 1;) {
            const std::size_t p = static_cast<std::size_t>(out.branches[b].parent);
            count[p] += count[b];
            sum[p] += sum[b];
        }
        for (std::size_t b = 1; b < branches; ++b) {
            Branch &br = out.branches[b];
            const double saddle = regions_.node_value(br.saddle_node);
            br.measures = make_measures(count[b] + 1.0, sum[b] + saddle, saddle,
                                        regions_.node_value(br.extremum_node),
                                        br.kind == BranchKind::Minimum);
        }
    }

    const ContourTree &tree_;
    const FieldView &field_;
    const ImportanceFn &importance_;
    TreeRegions regions_;
    uint32_t gmin_ = 0, gmax_ = 0;
    double f_min_ = 0, f_max_ = 0, mm3_ = 1;
    BranchMeasures root_;
    std::vector<uint32_t> cont_down_, cont_up_, rep_min_, rep_max_;
    std::vector<EndingBranch> ending_;
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
