#include "simplification.hpp"

#include "core/parallel_ranges.hpp"

#include <algorithm>
#include <numeric>

namespace arbor::topology {

namespace {

SimplificationCut finish(const BranchDecomposition &d, const std::vector<bool> &keep)
{
    SimplificationCut cut;
    const std::size_t n = d.branches.size();
    cut.kept_index.assign(n, -1);
    cut.label_of.assign(n, 0);
    // Parents come before children, so one pass resolves nearest ancestors.
    for (uint32_t b = 0; b < n; ++b) {
        if (b == 0 || keep[b]) {
            cut.kept_index[b] = static_cast<int32_t>(cut.kept.size());
            cut.kept.push_back(b);
            cut.label_of[b] = static_cast<uint32_t>(cut.kept_index[b]);
            const int32_t p = d.branches[b].parent;
            cut.kept_parent.push_back(p < 0 ? -1 : static_cast<int32_t>(cut.label_of[static_cast<uint32_t>(p)]));
        } else {
            cut.label_of[b] = cut.label_of[static_cast<uint32_t>(d.branches[b].parent)];
        }
    }
    return cut;
}

} // namespace

SimplificationCut cut_by_threshold(const BranchDecomposition &d, double threshold, const std::vector<bool> &eligible)
{
    std::vector<bool> keep(d.branches.size());
    for (std::size_t b = 0; b < d.branches.size(); ++b)
        keep[b] = d.branches[b].importance > threshold && (eligible.empty() || eligible[b]);
    return finish(d, keep);
}

SimplificationCut cut_by_count(const BranchDecomposition &d, std::size_t count, const std::vector<bool> &eligible)
{
    std::vector<uint32_t> idx;
    idx.reserve(d.branches.size());
    for (uint32_t b = 0; b < d.branches.size(); ++b)
        if (b == 0 || eligible.empty() || eligible[b])
            idx.push_back(b);
    std::stable_sort(idx.begin(), idx.end(), [&](uint32_t a, uint32_t b) {
        return d.branches[a].importance > d.branches[b].importance;
    });
    std::vector<bool> keep(d.branches.size(), false);
    for (std::size_t i = 0; i < std::min(count, idx.size()); ++i)
        keep[idx[i]] = true;
    return finish(d, keep);
}

LabelMap label_voxels(const ContourTree &tree, const BranchDecomposition &d, const SimplificationCut &cut)
{
    const std::size_t n = tree.vertex_arc.size();
    if (tree.arc_count() == 0)
        return LabelMap(n, 0u);
    std::vector<uint32_t> arc_label(tree.arc_count());
    for (std::size_t a = 0; a < arc_label.size(); ++a)
        arc_label[a] = cut.label_of[d.arc_branch[a]];
    // Sized (a LabelMap's pages are faulted in at once, then zeroed), then
    // filled on all cores: the gather is most of the work.
    LabelMap labels(n);
    const uint32_t *arc = tree.vertex_arc.data();
    uint32_t *out = labels.data();
    for_ranges(n, std::size_t{1} << 20, [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t v = begin; v < end; ++v)
            out[v] = arc_label[arc[v]];
    });
    // Nodes lie on several arcs: they take the branch that continues
    // through them.
    for (std::size_t x = 0; x < tree.node_count(); ++x)
        labels[tree.node_vertex[x]] = cut.label_of[d.node_branch[x]];
    return labels;
}

} // namespace arbor::topology
