#include "assignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace arbor::study {

std::vector<long> max_weight_assignment(const std::vector<double> &weight, std::size_t rows, std::size_t cols)
{
    if (weight.size() != rows * cols)
        throw std::invalid_argument("max_weight_assignment: the weights are not rows x cols");
    std::vector<long> match(rows, -1);
    if (rows == 0 || cols == 0)
        return match;
    double top = 0.0;
    for (const double w : weight) {
        if (!std::isfinite(w) || w < 0)
            throw std::invalid_argument("max_weight_assignment: weights must be finite and >= 0");
        top = std::max(top, w);
    }
    // Square cost matrix (padded with zero weights), minimised: cost = top - w.
    const std::size_t n = std::max(rows, cols);
    const auto cost = [&](std::size_t r, std::size_t c) {
        return top - (r < rows && c < cols ? weight[r * cols + c] : 0.0);
    };
    constexpr double kInf = std::numeric_limits<double>::infinity();
    // Potentials u (rows) and v (columns), 1-based with a virtual column 0;
    // p[c] is the row assigned to column c.
    std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
    std::vector<std::size_t> p(n + 1, 0), way(n + 1, 0);
    for (std::size_t r = 1; r <= n; ++r) {
        p[0] = r;
        std::size_t c0 = 0;
        std::vector<double> least(n + 1, kInf);
        std::vector<bool> used(n + 1, false);
        do {
            used[c0] = true;
            const std::size_t r0 = p[c0];
            double delta = kInf;
            std::size_t c1 = 0;
            for (std::size_t c = 1; c <= n; ++c) {
                if (used[c])
                    continue;
                const double reduced = cost(r0 - 1, c - 1) - u[r0] - v[c];
                if (reduced < least[c]) {
                    least[c] = reduced;
                    way[c] = c0;
                }
                if (least[c] < delta) {
                    delta = least[c];
                    c1 = c;
                }
            }
            for (std::size_t c = 0; c <= n; ++c) {
                if (used[c]) {
                    u[p[c]] += delta;
                    v[c] -= delta;
                } else {
                    least[c] -= delta;
                }
            }
            c0 = c1;
        } while (p[c0] != 0);
        // Augment along the alternating path.
        do {
            const std::size_t c1 = way[c0];
            p[c0] = p[c1];
            c0 = c1;
        } while (c0 != 0);
    }
    for (std::size_t c = 1; c <= n; ++c) {
        const std::size_t r = p[c] - 1;
        if (r < rows && c - 1 < cols && weight[r * cols + (c - 1)] > 0)
            match[r] = static_cast<long>(c - 1);
    }
    return match;
}

} // namespace arbor::study
