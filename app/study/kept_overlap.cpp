#include "kept_overlap.hpp"

#include <stdexcept>
#include <unordered_map>

namespace arbor::study {

namespace {

// One cut of a decomposition, asked for the kept label of a node.
class KeptLabels {
public:
    KeptLabels(const topology::BranchDecomposition &d, const std::vector<uint32_t> &kept) : d_(d), kept_(kept)
    {
        for (std::size_t k = 0; k < kept.size(); ++k)
            index_[kept[k]] = static_cast<uint32_t>(k);
    }
    // The label of the nearest kept ancestor of the branch through `node`.
    uint32_t at(uint32_t node) const
    {
        for (int64_t b = d_.node_branch[node]; b >= 0; b = d_.branches[static_cast<std::size_t>(b)].parent)
            if (const auto it = index_.find(static_cast<uint32_t>(b)); it != index_.end())
                return it->second;
        return 0; // the root is always kept
    }
    uint32_t extremum(std::size_t label) const { return d_.branches[kept_[label]].extremum_node; }
    std::size_t size() const { return kept_.size(); }

private:
    const topology::BranchDecomposition &d_;
    const std::vector<uint32_t> &kept_;
    std::unordered_map<uint32_t, uint32_t> index_;
};

} // namespace

KeptOverlap kept_overlap(const topology::BranchDecomposition &a, const std::vector<uint32_t> &kept_a,
                         const topology::BranchDecomposition &b, const std::vector<uint32_t> &kept_b)
{
    if (a.node_branch.size() != b.node_branch.size())
        throw std::invalid_argument("kept_overlap: the decompositions are of different trees");
    if (kept_a.empty() || kept_b.empty())
        throw std::invalid_argument("kept_overlap: a cut keeps at least the root");
    const KeptLabels A(a, kept_a), B(b, kept_b);
    KeptOverlap o;
    for (std::size_t la = 1; la < A.size(); ++la) {
        const uint32_t lb = B.at(A.extremum(la));
        if (lb != 0 && A.at(B.extremum(lb)) == la)
            ++o.shared;
    }
    o.only_a = A.size() - 1 - o.shared;
    o.only_b = B.size() - 1 - o.shared;
    const std::size_t all = o.shared + o.only_a + o.only_b;
    o.jaccard = all ? static_cast<double>(o.shared) / static_cast<double>(all) : 1.0;
    return o;
}

} // namespace arbor::study
