// dense_assignment.hpp - optimal assignments on a small square cost matrix,
// for the essential points of two diagrams, which are matched only among
// themselves (never to the diagonal).  O(k^3); k is the number of essential
// points of a dimension (one for a connected volume).
#pragma once

#include <vector>

namespace arbor::topology {

// cost[i][j] >= 0; returns, for each row, its column in an assignment of
// least total cost (Hungarian method with potentials).
std::vector<int> min_sum_assignment(const std::vector<std::vector<long double>> &cost);

// cost[i][j] >= 0; an assignment whose largest cost is least.
std::vector<int> min_max_assignment(const std::vector<std::vector<long double>> &cost);

} // namespace arbor::topology
