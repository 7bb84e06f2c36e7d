#include "dense_assignment.hpp"

#include <algorithm>
#include <limits>

namespace arbor::topology {

std::vector<int> min_sum_assignment(const std::vector<std::vector<long double>> &cost)
{
    // Kuhn-Munkres with row and column potentials, one row added at a time
    // along a shortest augmenting path (1-based; column 0 is a sentinel).
    const int n = static_cast<int>(cost.size());
    const long double inf = std::numeric_limits<long double>::infinity();
    std::vector<long double> u(n + 1, 0.0L), v(n + 1, 0.0L);
    std::vector<int> row_of(n + 1, 0), way(n + 1, 0);
    for (int i = 1; i <= n; ++i) {
        row_of[0] = i;
        int j0 = 0;
        std::vector<long double> min_slack(n + 1, inf);
        std::vector<char> used(n + 1, 0);
        do {
            used[j0] = 1;
            const int i0 = row_of[j0];
            long double delta = inf;
            int j1 = 0;
            for (int j = 1; j <= n; ++j) {
                if (used[j])
                    continue;
                const long double slack = cost[i0 - 1][j - 1] - u[i0] - v[j];
                if (slack < min_slack[j]) {
                    min_slack[j] = slack;
                    way[j] = j0;
                }
                if (min_slack[j] < delta) {
                    delta = min_slack[j];
                    j1 = j;
                }
            }
            for (int j = 0; j <= n; ++j) {
                if (used[j]) {
                    u[row_of[j]] += delta;
                    v[j] -= delta;
                } else {
                    min_slack[j] -= delta;
                }
            }
            j0 = j1;
        } while (row_of[j0] != 0);
        do {
            const int j1 = way[j0];
            row_of[j0] = row_of[j1];
            j0 = j1;
        } while (j0 != 0);
    }
    std::vector<int> column(n, -1);
    for (int j = 1; j <= n; ++j)
        column[row_of[j] - 1] = j - 1;
    return column;
}

namespace {

// Kuhn's augmenting paths on the pairs with cost <= t; the column of each
// row, or an empty vector when not every row can be assigned.
std::vector<int> perfect_within(const std::vector<std::vector<long double>> &cost, long double t)
{
    const int n = static_cast<int>(cost.size());
    std::vector<int> row_of(n, -1);
    std::vector<char> seen;
    const auto augment = [&](auto &self, int i) -> bool {
        for (int j = 0; j < n; ++j) {
            if (cost[i][j] > t || seen[j])
                continue;
            seen[j] = 1;
            if (row_of[j] < 0 || self(self, row_of[j])) {
                row_of[j] = i;
                return true;
            }
        }
        return false;
    };
    for (int i = 0; i < n; ++i) {
        seen.assign(n, 0);
        if (!augment(augment, i))
            return {};
    }
    std::vector<int> column(n);
    for (int j = 0; j < n; ++j)
        column[row_of[j]] = j;
    return column;
}

} // namespace

std::vector<int> min_max_assignment(const std::vector<std::vector<long double>> &cost)
{
    std::vector<long double> values;
    for (const auto &row : cost)
        values.insert(values.end(), row.begin(), row.end());
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    if (values.empty())
        return {};
    std::size_t first = 0, last = values.size() - 1; // the largest value always admits one
    while (first < last) {
        const std::size_t mid = first + (last - first) / 2;
        if (!perfect_within(cost, values[mid]).empty())
            last = mid;
        else
            first = mid + 1;
    }
    return perfect_within(cost, values[first]);
}

} // namespace arbor::topology
