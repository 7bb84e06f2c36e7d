// assignment.hpp - the linear assignment problem: a one-to-one matching of
// rows to columns that maximises the total weight (Kuhn-Munkres, the
// Hungarian method with potentials, O(n^3) for n = max(rows, cols)).
//
// A comparison study matches kept regions to ground-truth structures with
// it, so that one region cannot be credited for several structures.
#pragma once

#include <cstddef>
#include <vector>

namespace arbor::study {

// `weight` is rows x cols, row-major, every entry finite and >= 0.  Returns
// for each row its column, or -1 when the row is left unmatched (there are
// more rows than columns, or its best share is a zero weight: a pair of
// weight 0 is no match).  The total weight of the pairs is the maximum over
// all one-to-one matchings.
std::vector<long> max_weight_assignment(const std::vector<double> &weight, std::size_t rows, std::size_t cols);

} // namespace arbor::study
