#include "diagram_distance.hpp"

#include "bottleneck_distance.hpp"
#include "dense_assignment.hpp"
#include "wasserstein_distance.hpp"

#include "core/stopwatch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace arbor::topology {

namespace {

// Essential points beyond this many per dimension are refused: their dense
// O(k^3) assignment would take minutes.
constexpr std::size_t kMaxEssential = 2000;

void check(const PersistenceDiagram &d, const char *name)
{
    for (std::size_t i = 0; i < d.points.size(); ++i) {
        const DiagramPoint &p = d.points[i];
        if (!std::isfinite(p.birth) || !std::isfinite(p.death))
            throw std::invalid_argument(std::string("diagram ") + name + ": point " + std::to_string(i + 1) +
                                        " has a value that is not a finite number");
        if (p.death < p.birth)
            throw std::invalid_argument(std::string("diagram ") + name + ": point " + std::to_string(i + 1) +
                                        " dies before it is born");
    }
}

struct Split {
    std::vector<PlanePoint> finite, essential;
};

Split points_of(const PersistenceDiagram &d, int dimension)
{
    Split s;
    for (const DiagramPoint &p : d.points)
        if (p.dimension == dimension)
            (p.essential ? s.essential : s.finite).push_back({p.birth, p.death});
    return s;
}

DimensionDistance distance_in(const PersistenceDiagram &a, const PersistenceDiagram &b, int dimension,
                              const DiagramDistanceOptions &options)
{
    Stopwatch clock;
    const Split sa = points_of(a, dimension), sb = points_of(b, dimension);
    DimensionDistance r;
    r.dimension = dimension;
    r.points_a = sa.finite.size();
    r.points_b = sb.finite.size();
    r.essential_a = sa.essential.size();
    r.essential_b = sb.essential.size();
    const bool bottleneck = options.metric == DiagramMetric::Bottleneck;
    if (r.essential_a != r.essential_b) {
        r.distance = std::numeric_limits<double>::infinity();
        r.cost = std::numeric_limits<long double>::infinity();
        r.seconds = clock.lap();
        return r;
    }
    if (r.essential_a > kMaxEssential)
        throw std::invalid_argument("dimension " + std::to_string(dimension) + " has " +
                                    std::to_string(r.essential_a) + " essential points; at most " +
                                    std::to_string(kMaxEssential) + " are supported");

    // Essential points among themselves.
    const std::size_t k = sa.essential.size();
    std::vector<std::vector<long double>> cost(k, std::vector<long double>(k));
    for (std::size_t i = 0; i < k; ++i)
        for (std::size_t j = 0; j < k; ++j) {
            const long double d = linf_distance(sa.essential[i], sb.essential[j]);
            cost[i][j] = bottleneck ? d : std::pow(d, static_cast<long double>(options.p));
        }
    long double essential_cost = 0.0L; // largest (bottleneck) or sum (Wasserstein)
    if (k > 0) {
        const std::vector<int> column = bottleneck ? min_max_assignment(cost) : min_sum_assignment(cost);
        for (std::size_t i = 0; i < k; ++i)
            essential_cost = bottleneck ? std::max(essential_cost, cost[i][column[i]])
                                        : essential_cost + cost[i][column[i]];
    }

    if (bottleneck) {
        const BottleneckResult f = bottleneck_distance(sa.finite, sb.finite);
        r.distance = std::max(f.distance, static_cast<double>(essential_cost));
        r.matched_pairs = f.matched_pairs;
    } else {
        const WassersteinResult f = wasserstein_distance(sa.finite, sb.finite, options.p);
        r.cost = f.cost + essential_cost;
        r.distance = static_cast<double>(std::pow(r.cost, 1.0L / options.p));
        r.matched_pairs = f.matched_pairs;
        r.exact = f.exact;
        if (!f.exact) {
            const long double lower_finite = std::pow(static_cast<long double>(f.distance - f.error_bound), options.p);
            const long double lower = std::pow(lower_finite + essential_cost, 1.0L / options.p);
            r.error_bound = static_cast<double>(r.distance - lower);
        }
    }
    r.seconds = clock.lap();
    return r;
}

} // namespace

DiagramDistance diagram_distance(const PersistenceDiagram &a, const PersistenceDiagram &b,
                                 const DiagramDistanceOptions &options)
{
    if (options.metric == DiagramMetric::Wasserstein && (!(options.p >= 1.0) || !std::isfinite(options.p)))
        throw std::invalid_argument("the Wasserstein exponent p must be a number >= 1");
    check(a, "A");
    check(b, "B");
    std::vector<int> dims = diagram_dimensions(a, b);
    if (options.dimension)
        dims = {*options.dimension};
    DiagramDistance result;
    long double sum = 0.0L;
    double largest = 0.0;
    for (int dim : dims) {
        result.dimensions.push_back(distance_in(a, b, dim, options));
        const DimensionDistance &d = result.dimensions.back();
        sum += d.cost;
        largest = std::max(largest, d.distance);
        result.exact = result.exact && d.exact;
    }
    result.total = options.metric == DiagramMetric::Bottleneck
                       ? largest
                       : static_cast<double>(std::pow(sum, 1.0L / options.p));
    return result;
}

} // namespace arbor::topology
