// diagram_distance.hpp - distances between two persistence diagrams, per
// homology dimension, exactly (bottleneck_distance.hpp,
// wasserstein_distance.hpp).
//
// Conventions:
//   - ground distance L-infinity; a finite point may be matched to the
//     diagonal at cost (death - birth) / 2;
//   - points are matched only within their dimension; the distance of each
//     dimension is reported, and the total is the distance over all points
//     with that constraint: the largest per-dimension distance (bottleneck),
//     (sum over dimensions of W_p^p)^(1/p) (Wasserstein);
//   - essential points (classes that never die: in a volume's diagram the
//     global minimum - global maximum pair) are matched only to essential
//     points of the same dimension, never to the diagonal, by the same
//     L-infinity distance of (birth, death) (their death is the global
//     maximum, a finite value, so it takes part); when the two diagrams have
//     different numbers of them in a dimension the distance is infinite (the
//     convention of TTK and Hera).
#pragma once

#include "persistence_diagram.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace arbor::topology {

enum class DiagramMetric { Bottleneck, Wasserstein };

struct DiagramDistanceOptions {
    DiagramMetric metric = DiagramMetric::Wasserstein;
    double p = 2.0;                // Wasserstein exponent, >= 1
    std::optional<int> dimension;  // only this dimension
};

struct DimensionDistance {
    int dimension = 0;
    double distance = 0.0;            // +infinity when the essential counts differ
    long double cost = 0.0;           // Wasserstein: distance^p
    std::size_t points_a = 0, points_b = 0;       // finite points
    std::size_t essential_a = 0, essential_b = 0;
    std::size_t matched_pairs = 0;    // finite points matched to finite points (the rest: diagonal)
    bool exact = true;                // see wasserstein_distance.hpp
    double error_bound = 0.0;
    double seconds = 0.0;
};

struct DiagramDistance {
    std::vector<DimensionDistance> dimensions;
    double total = 0.0;
    bool exact = true;
};

// Throws std::invalid_argument for points with death < birth or values that
// are not finite, and for p < 1.
DiagramDistance diagram_distance(const PersistenceDiagram &a, const PersistenceDiagram &b,
                                 const DiagramDistanceOptions &options);

} // namespace arbor::topology
