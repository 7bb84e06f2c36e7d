#include "importance_knee.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace arbor::topology {

KneeChoice knee_branch_count(const BranchDecomposition &d, std::size_t min_keep, std::size_t max_keep,
                             std::size_t max_ranks, const std::vector<bool> &eligible)
{
    std::vector<double> importance;
    for (std::size_t b = 1; b < d.branches.size(); ++b)
        if (d.branches[b].importance > 0 && (eligible.empty() || eligible[b]))
            importance.push_back(d.branches[b].importance);
    const std::size_t n = std::min(importance.size(), max_ranks);
    std::partial_sort(importance.begin(), importance.begin() + static_cast<std::ptrdiff_t>(n), importance.end(),
                      std::greater<>());
    KneeChoice choice;
    choice.considered = n;
    std::size_t knee = n; // keep every ranked branch when there is no bend
    if (n >= 3) {
        const double x0 = 0.0, x1 = static_cast<double>(n - 1);
        const double y0 = std::log(importance[0]), y1 = std::log(importance[n - 1]);
        double best = 0.0;
        for (std::size_t r = 1; r + 1 < n; ++r) {
            const double x = static_cast<double>(r), y = std::log(importance[r]);
            // How far the curve lies below the chord (both axes normalised).
            const double chord = y0 + (y1 - y0) * (x - x0) / (x1 - x0);
            const double below = (chord - y) / (y0 - y1 > 0 ? y0 - y1 : 1.0);
            if (below > best) {
                best = below;
                knee = r + 1; // ranks 1..r+1 are kept
            }
        }
    }
    choice.keep = std::clamp(knee + 1, min_keep, std::max(min_keep, max_keep)); // + the root
    std::size_t candidates = d.branches.size();
    if (!eligible.empty())
        candidates = 1 + static_cast<std::size_t>(std::count(eligible.begin() + 1, eligible.end(), true));
    choice.keep = std::min(choice.keep, candidates);
    return choice;
}

} // namespace arbor::topology
