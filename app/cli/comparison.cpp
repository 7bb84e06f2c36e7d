#include "comparison.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace arbor::cli {

namespace {

uint32_t extremum_vertex(const ComparedSimplifier &c, const topology::ContourTree &tree, std::size_t label)
{
    return tree.node_vertex[c.run.branches.branches[c.run.cut.kept[label]].extremum_node];
}

} // namespace

std::vector<Overlap> kept_overlaps(const std::vector<ComparedSimplifier> &runs, const topology::ContourTree &tree)
{
    std::vector<Overlap> out;
    for (std::size_t a = 0; a < runs.size(); ++a)
        for (std::size_t b = a + 1; b < runs.size(); ++b) {
            const ComparedSimplifier &A = runs[a], &B = runs[b];
            Overlap o;
            o.a = a;
            o.b = b;
            for (std::size_t la = 1; la < A.run.cut.kept.size(); ++la) {
                const uint32_t lb = B.labels[extremum_vertex(A, tree, la)];
                if (lb != 0 && A.labels[extremum_vertex(B, tree, lb)] == la)
                    ++o.shared;
            }
            o.only_a = A.run.cut.kept.size() - 1 - o.shared;
            o.only_b = B.run.cut.kept.size() - 1 - o.shared;
            const std::size_t uni = o.shared + o.only_a + o.only_b;
            o.jaccard = uni ? static_cast<double>(o.shared) / static_cast<double>(uni) : 1.0;
            out.push_back(o);
        }
    return out;
}

std::vector<TruthScore> truth_scores(const Volume &truth, const std::vector<ComparedSimplifier> &runs)
{
    const std::size_t n = truth.voxel_count();
    for (const ComparedSimplifier &c : runs)
        if (c.labels.size() != n)
            throw std::invalid_argument("the ground-truth labels have " + std::to_string(n) +
                                        " voxels, the volume " + std::to_string(c.labels.size()) +
                                        ": they must have the same dims");
    std::vector<uint32_t> t(n);
    for (std::size_t v = 0; v < n; ++v) {
        const double x = truth.value(v);
        if (!(x >= 0) || x != std::floor(x) || x > 4294967295.0)
            throw std::invalid_argument("the ground-truth labels must be non-negative integers (voxel " +
                                        std::to_string(v) + " holds " + std::to_string(x) + ")");
        t[v] = static_cast<uint32_t>(x);
    }
    std::map<uint32_t, uint64_t> truth_size;
    for (uint32_t x : t)
        if (x)
            ++truth_size[x];
    if (truth_size.size() > 10000)
        throw std::invalid_argument("the ground truth has " + std::to_string(truth_size.size()) +
                                    " labels; a label map with at most 10000 is expected");
    std::vector<TruthScore> out;
    for (const auto &[label, size] : truth_size)
        out.push_back({label, size, std::vector<TruthMatch>(runs.size())});
    std::unordered_map<uint32_t, std::size_t> index;
    for (std::size_t i = 0; i < out.size(); ++i)
        index[out[i].truth_label] = i;

    for (std::size_t r = 0; r < runs.size(); ++r) {
        const std::vector<uint32_t> &s = runs[r].labels;
        std::vector<uint64_t> kept_size(runs[r].run.cut.kept.size(), 0);
        std::unordered_map<uint64_t, uint64_t> both; // (truth index << 32 | kept label) -> voxels
        for (std::size_t v = 0; v < n; ++v) {
            ++kept_size[s[v]];
            if (t[v])
                ++both[(static_cast<uint64_t>(index[t[v]]) << 32) | s[v]];
        }
        for (const auto &[key, count] : both) {
            TruthScore &score = out[key >> 32];
            const uint32_t kept = static_cast<uint32_t>(key);
            const double dice = 2.0 * static_cast<double>(count) /
                                static_cast<double>(score.voxels + kept_size[kept]);
            if (dice > score.best[r].dice)
                score.best[r] = {kept, dice};
        }
    }
    return out;
}

} // namespace arbor::cli
