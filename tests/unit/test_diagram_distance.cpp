// Exact diagram distances against independent oracles:
//   - brute force: every matching of small diagrams (up to 6 points a side,
//     each point to a point of the other diagram or to the diagonal);
//   - on medium diagrams (tens of points) a dense min-cost flow (successive
//     shortest paths, Bellman-Ford) and a dense bottleneck search over the
//     full augmented matrix, written here without the library's code;
//   - known distances worked out by hand;
//   - metric properties (identity, symmetry, triangle inequality, W_p
//     non-increasing in p and never below the bottleneck) on larger random
//     diagrams, where no oracle is fast enough.
#include "topology/bottleneck_distance.hpp"
#include "topology/diagram_distance.hpp"
#include "topology/wasserstein_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace arbor::topology {
namespace {

using Points = std::vector<PlanePoint>;

// --- the oracles' own geometry ------------------------------------------------

long double chebyshev(PlanePoint a, PlanePoint b)
{
    return std::max(std::fabs(static_cast<long double>(a.x) - b.x), std::fabs(static_cast<long double>(a.y) - b.y));
}

long double to_diagonal(PlanePoint a)
{
    return (static_cast<long double>(a.y) - a.x) / 2;
}

long double power(long double v, double p)
{
    return std::pow(v, static_cast<long double>(p));
}

// Every matching: a[i] to b[choice[i]] or to the diagonal (-1); unmatched b
// to the diagonal.  Returns the least cost under `combine` (max or sum of
// powers).
long double brute_force(const Points &a, const Points &b, bool bottleneck, double p)
{
    std::vector<int> choice(a.size(), -1);
    std::vector<char> used(b.size(), 0);
    long double best = std::numeric_limits<long double>::infinity();
    const auto cost_of = [&](long double d) { return bottleneck ? d : power(d, p); };
    std::function<void(std::size_t)> rec = [&](std::size_t i) {
        if (i == a.size()) {
            long double total = 0;
            const auto add = [&](long double c) { total = bottleneck ? std::max(total, c) : total + c; };
            for (std::size_t k = 0; k < a.size(); ++k)
                add(choice[k] < 0 ? cost_of(to_diagonal(a[k])) : cost_of(chebyshev(a[k], b[choice[k]])));
            for (std::size_t j = 0; j < b.size(); ++j)
                if (!used[j])
                    add(cost_of(to_diagonal(b[j])));
            best = std::min(best, total);
            return;
        }
        choice[i] = -1;
        rec(i + 1);
        for (std::size_t j = 0; j < b.size(); ++j)
            if (!used[j]) {
                used[j] = 1;
                choice[i] = static_cast<int>(j);
                rec(i + 1);
                used[j] = 0;
            }
        choice[i] = -1;
    };
    rec(0);
    return best;
}

// The augmented square matrix: rows A then B's diagonal copies, columns B
// then A's diagonal copies.
std::vector<std::vector<long double>> augmented(const Points &a, const Points &b, bool bottleneck, double p)
{
    const std::size_t n = a.size() + b.size();
    const long double inf = std::numeric_limits<long double>::infinity();
    const auto cost_of = [&](long double d) { return bottleneck ? d : power(d, p); };
    std::vector<std::vector<long double>> c(n, std::vector<long double>(n, inf));
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (std::size_t j = 0; j < b.size(); ++j)
            c[i][j] = cost_of(chebyshev(a[i], b[j]));
        c[i][b.size() + i] = cost_of(to_diagonal(a[i]));
    }
    for (std::size_t j = 0; j < b.size(); ++j) {
        c[a.size() + j][j] = cost_of(to_diagonal(b[j]));
        for (std::size_t i = 0; i < a.size(); ++i)
            c[a.size() + j][b.size() + i] = 0;
    }
    return c;
}

// Min-cost perfect matching by successive shortest paths with Bellman-Ford
// on the residual graph of the dense augmented matrix.
long double dense_min_cost(const std::vector<std::vector<long double>> &c)
{
    const int n = static_cast<int>(c.size());
    const long double inf = std::numeric_limits<long double>::infinity();
    std::vector<int> row_of(n, -1), col_of(n, -1);
    for (int step = 0; step < n; ++step) {
        // Nodes: rows 0..n-1, columns n..2n-1.  Paths start at free rows.
        std::vector<long double> dist(2 * n, inf);
        std::vector<int> prev(2 * n, -1);
        for (int i = 0; i < n; ++i)
            if (col_of[i] < 0)
                dist[i] = 0;
        for (int round = 0; round < 2 * n; ++round) {
            bool changed = false;
            for (int i = 0; i < n; ++i) {
                if (dist[i] == inf)
                    continue;
                for (int j = 0; j < n; ++j)
                    if (c[i][j] < inf && col_of[i] != j && dist[i] + c[i][j] < dist[n + j]) {
                        dist[n + j] = dist[i] + c[i][j];
                        prev[n + j] = i;
                        changed = true;
                    }
            }
            for (int j = 0; j < n; ++j) {
                const int i = row_of[j];
                if (i >= 0 && dist[n + j] < inf && dist[n + j] - c[i][j] < dist[i]) {
                    dist[i] = dist[n + j] - c[i][j];
                    prev[i] = n + j;
                    changed = true;
                }
            }
            if (!changed)
                break;
        }
        int end = -1;
        for (int j = 0; j < n; ++j)
            if (row_of[j] < 0 && dist[n + j] < inf && (end < 0 || dist[n + j] < dist[n + end]))
                end = j;
        if (end < 0)
            return inf;
        for (int node = n + end; node >= 0;) {
            const int i = prev[node];
            const int j = node - n;
            row_of[j] = i;
            col_of[i] = j;
            node = prev[i]; // the column i leaves, or -1 at the free row the path starts from
        }
    }
    long double total = 0;
    for (int i = 0; i < n; ++i)
        total += c[i][col_of[i]];
    return total;
}

// Least t admitting a perfect matching of the augmented matrix (Kuhn's
// algorithm for each candidate).
long double dense_bottleneck(const std::vector<std::vector<long double>> &c)
{
    const int n = static_cast<int>(c.size());
    std::vector<long double> values;
    for (const auto &row : c)
        for (long double v : row)
            if (std::isfinite(v))
                values.push_back(v);
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    const auto perfect = [&](long double t) {
        std::vector<int> row_of(n, -1);
        std::vector<char> seen;
        std::function<bool(int)> aug = [&](int i) {
            for (int j = 0; j < n; ++j)
                if (c[i][j] <= t && !seen[j]) {
                    seen[j] = 1;
                    if (row_of[j] < 0 || aug(row_of[j])) {
                        row_of[j] = i;
                        return true;
                    }
                }
            return false;
        };
        for (int i = 0; i < n; ++i) {
            seen.assign(n, 0);
            if (!aug(i))
                return false;
        }
        return true;
    };
    for (long double v : values)
        if (perfect(v))
            return v;
    return 0;
}

// --- random diagrams ----------------------------------------------------------

Points random_points(std::mt19937 &rng, std::size_t n, bool integers, double range = 10.0)
{
    Points out;
    std::uniform_real_distribution<double> u(0.0, range);
    std::uniform_int_distribution<int> ui(0, static_cast<int>(range));
    for (std::size_t i = 0; i < n; ++i) {
        // Real values as a float32 volume holds them: their differences are
        // exact in double, as the library's exactness claim assumes.
        double x = integers ? ui(rng) : static_cast<float>(u(rng));
        double y = integers ? ui(rng) : static_cast<float>(u(rng));
        if (y < x)
            std::swap(x, y);
        out.push_back({x, y});
    }
    return out;
}

long double wasserstein_power(const Points &a, const Points &b, double p)
{
    return wasserstein_distance(a, b, p).cost;
}

// --- brute force ----------------------------------------------------------------

TEST(DiagramDistanceBruteForce, BottleneckEqualsEveryMatchingsBest)
{
    std::mt19937 rng(11);
    for (int trial = 0; trial < 400; ++trial) {
        const bool integers = trial % 2 == 0;
        const Points a = random_points(rng, rng() % 7, integers), b = random_points(rng, rng() % 7, integers);
        const long double want = brute_force(a, b, true, 0);
        const BottleneckResult got = bottleneck_distance(a, b);
        ASSERT_EQ(static_cast<long double>(got.distance), want) << "trial " << trial;
        ASSERT_EQ(static_cast<long double>(bottleneck_distance(b, a).distance), want) << "trial " << trial;
    }
}

TEST(DiagramDistanceBruteForce, WassersteinEqualsEveryMatchingsBest)
{
    std::mt19937 rng(12);
    for (double p : {1.0, 2.0, 3.0, 1.5}) {
        for (int trial = 0; trial < 200; ++trial) {
            const bool integers = trial % 2 == 0;
            const Points a = random_points(rng, rng() % 7, integers), b = random_points(rng, rng() % 7, integers);
            const long double want = brute_force(a, b, false, p);
            const WassersteinResult got = wasserstein_distance(a, b, p);
            if (integers && p == std::floor(p)) {
                // Integer costs: exactly the optimum.
                ASSERT_TRUE(got.exact);
                ASSERT_EQ(got.cost, want) << "p " << p << " trial " << trial;
            } else {
                ASSERT_NEAR(static_cast<double>(got.cost), static_cast<double>(want), 1e-12 * (1 + want))
                    << "p " << p << " trial " << trial;
                ASSERT_LE(got.error_bound, 1e-9);
            }
        }
    }
}

TEST(DiagramDistanceBruteForce, EssentialPointsMatchOnlyEachOther)
{
    // Three essential points a side, against every permutation.
    std::mt19937 rng(13);
    for (int trial = 0; trial < 50; ++trial) {
        PersistenceDiagram a, b;
        const Points ea = random_points(rng, 3, true, 50), eb = random_points(rng, 3, true, 50);
        for (PlanePoint q : ea)
            a.points.push_back({q.x, q.y, 0, true});
        for (PlanePoint q : eb)
            b.points.push_back({q.x, q.y, 0, true});
        std::vector<int> perm{0, 1, 2};
        long double best_max = std::numeric_limits<long double>::infinity(), best_sum = best_max;
        do {
            long double mx = 0, sum = 0;
            for (int i = 0; i < 3; ++i) {
                const long double d = chebyshev(ea[i], eb[perm[i]]);
                mx = std::max(mx, d);
                sum += d * d;
            }
            best_max = std::min(best_max, mx);
            best_sum = std::min(best_sum, sum);
        } while (std::next_permutation(perm.begin(), perm.end()));
        const DiagramDistance bn = diagram_distance(a, b, {DiagramMetric::Bottleneck, 2.0, {}});
        const DiagramDistance w2 = diagram_distance(a, b, {DiagramMetric::Wasserstein, 2.0, {}});
        EXPECT_EQ(static_cast<long double>(bn.total), best_max);
        EXPECT_EQ(w2.dimensions.at(0).cost, best_sum);
    }
}

// --- dense oracles on medium diagrams -----------------------------------------

TEST(DiagramDistanceDense, MediumDiagramsAgreeWithDenseOracles)
{
    std::mt19937 rng(14);
    for (int trial = 0; trial < 24; ++trial) {
        const bool integers = trial % 3 != 0;
        const Points a = random_points(rng, 10 + rng() % 30, integers, 40),
                     b = random_points(rng, 10 + rng() % 30, integers, 40);
        const double p = trial % 2 ? 2.0 : 1.0;
        EXPECT_EQ(static_cast<long double>(bottleneck_distance(a, b).distance),
                  dense_bottleneck(augmented(a, b, true, 0)))
            << "trial " << trial;
        const long double want = dense_min_cost(augmented(a, b, false, p));
        const long double got = wasserstein_power(a, b, p);
        if (integers)
            EXPECT_EQ(got, want) << "trial " << trial;
        else
            EXPECT_NEAR(static_cast<double>(got), static_cast<double>(want), 1e-9 * (1 + want)) << "trial " << trial;
    }
}

// --- known answers --------------------------------------------------------------

TEST(DiagramDistanceKnown, HandComputedCases)
{
    // (0,4) against (1,4): the pair costs 1, the diagonal 2 and 1.5.
    EXPECT_EQ(bottleneck_distance(Points{{0, 4}}, Points{{1, 4}}).distance, 1.0);
    EXPECT_EQ(wasserstein_distance(Points{{0, 4}}, Points{{1, 4}}, 2).distance, 1.0);
    // (0,2) against (10,14): apart they cost 10, to the diagonal 1 and 2.
    EXPECT_EQ(bottleneck_distance(Points{{0, 2}}, Points{{10, 14}}).distance, 2.0);
    EXPECT_DOUBLE_EQ(wasserstein_distance(Points{{0, 2}}, Points{{10, 14}}, 2).distance, std::sqrt(5.0));
    EXPECT_EQ(wasserstein_distance(Points{{0, 2}}, Points{{10, 14}}, 1).distance, 3.0);
    // An empty diagram: everything to the diagonal.
    EXPECT_EQ(bottleneck_distance(Points{{0, 6}, {1, 3}}, Points{}).distance, 3.0);
    EXPECT_DOUBLE_EQ(wasserstein_distance(Points{{0, 6}, {1, 3}}, Points{}, 2).distance, std::sqrt(9.0 + 1.0));
    // Points on the diagonal cost nothing.
    EXPECT_EQ(bottleneck_distance(Points{{5, 5}, {7, 7}}, Points{{1, 1}}).distance, 0.0);
    // Two points each, crossing is worse: (0,10),(20,30) vs (1,10),(20,32):
    // straight 1 and 2 (W2^2 = 5, bottleneck 2).
    EXPECT_EQ(bottleneck_distance(Points{{0, 10}, {20, 30}}, Points{{1, 10}, {20, 32}}).distance, 2.0);
    EXPECT_EQ(wasserstein_distance(Points{{0, 10}, {20, 30}}, Points{{1, 10}, {20, 32}}, 2).cost, 5.0L);
}

TEST(DiagramDistanceKnown, DimensionsAndEssentialPoints)
{
    PersistenceDiagram a, b;
    a.points = {{0, 255, 0, true}, {10, 20, 0, false}, {100, 200, 2, false}};
    b.points = {{2, 250, 0, true}, {10, 22, 0, false}, {100, 190, 2, false}, {50, 54, 2, false}};
    const DiagramDistance bn = diagram_distance(a, b, {DiagramMetric::Bottleneck, 2.0, {}});
    ASSERT_EQ(bn.dimensions.size(), 2u);
    EXPECT_EQ(bn.dimensions[0].distance, 5.0);  // the essential pair: |255 - 250|
    EXPECT_EQ(bn.dimensions[1].distance, 10.0); // (100,200) - (100,190)
    EXPECT_EQ(bn.total, 10.0);
    const DiagramDistance w = diagram_distance(a, b, {DiagramMetric::Wasserstein, 2.0, {}});
    EXPECT_EQ(w.dimensions[0].cost, 25.0L + 4.0L);         // essential 5^2, (10,20)-(10,22) 2^2
    EXPECT_EQ(w.dimensions[1].cost, 100.0L + 4.0L);        // 10^2, (50,54) to the diagonal 2^2
    EXPECT_DOUBLE_EQ(w.total, std::sqrt(133.0));
    EXPECT_EQ(w.dimensions[1].matched_pairs, 1u);
    const DiagramDistance only2 = diagram_distance(a, b, {DiagramMetric::Wasserstein, 2.0, 2});
    ASSERT_EQ(only2.dimensions.size(), 1u);
    EXPECT_DOUBLE_EQ(only2.total, std::sqrt(104.0));
    // A diagram without its essential pair is infinitely far.
    b.points.erase(b.points.begin());
    EXPECT_TRUE(std::isinf(diagram_distance(a, b, {DiagramMetric::Bottleneck, 2.0, {}}).total));
    EXPECT_TRUE(std::isinf(diagram_distance(a, b, {DiagramMetric::Wasserstein, 2.0, {}}).total));
}

TEST(DiagramDistanceKnown, BadInputIsRefused)
{
    PersistenceDiagram a, b;
    a.points = {{5, 3, 0, false}};
    EXPECT_THROW(diagram_distance(a, b, {}), std::invalid_argument);
    a.points = {{0, std::nan(""), 0, false}};
    EXPECT_THROW(diagram_distance(a, b, {}), std::invalid_argument);
    a.points = {{0, 1, 0, false}};
    EXPECT_THROW(diagram_distance(a, b, {DiagramMetric::Wasserstein, 0.5, {}}), std::invalid_argument);
}

// --- properties on larger diagrams ---------------------------------------------

TEST(DiagramDistanceProperties, MetricAxiomsOnRandomDiagrams)
{
    std::mt19937 rng(15);
    for (int trial = 0; trial < 6; ++trial) {
        const bool integers = trial % 2 == 0;
        const std::size_t n = 300 + rng() % 300;
        const Points a = random_points(rng, n, integers, 200), b = random_points(rng, n + 40, integers, 200),
                     c = random_points(rng, n - 30, integers, 200);
        const double ab = bottleneck_distance(a, b).distance, bc = bottleneck_distance(b, c).distance,
                     ac = bottleneck_distance(a, c).distance;
        EXPECT_EQ(bottleneck_distance(a, a).distance, 0.0);
        EXPECT_EQ(bottleneck_distance(b, a).distance, ab);
        EXPECT_LE(ac, ab + bc);
        for (double p : {1.0, 2.0}) {
            const double wab = wasserstein_distance(a, b, p).distance, wbc = wasserstein_distance(b, c, p).distance,
                         wac = wasserstein_distance(a, c, p).distance;
            EXPECT_EQ(wasserstein_distance(a, a, p).distance, 0.0);
            EXPECT_DOUBLE_EQ(wasserstein_distance(b, a, p).distance, wab);
            EXPECT_LE(wac, (wab + wbc) * (1 + 1e-12));
            EXPECT_GE(wab, ab); // W_p >= W_inf
        }
        EXPECT_GE(wasserstein_distance(a, b, 1).distance, wasserstein_distance(a, b, 2).distance);
        EXPECT_GE(wasserstein_distance(a, b, 2).distance, wasserstein_distance(a, b, 3).distance);
    }
}

// A diagram shaped like a noisy scan's: most pairs of low persistence near
// the diagonal, a few structures far from it.
Points scan_like(std::mt19937 &rng, std::size_t n, bool integers)
{
    std::uniform_real_distribution<double> birth(0.0, 255.0), far(20.0, 200.0), unit(0.0, 1.0);
    std::exponential_distribution<double> noise(1.0 / 4.0);
    Points out;
    for (std::size_t i = 0; i < n; ++i) {
        double b = birth(rng), pers = unit(rng) < 0.01 ? far(rng) : noise(rng);
        if (integers) {
            b = std::round(b);
            pers = std::round(pers);
        } else {
            b = static_cast<float>(b);
            pers = static_cast<float>(pers);
        }
        out.push_back({b, static_cast<double>(static_cast<float>(b + pers))});
    }
    return out;
}

TEST(DiagramDistanceProperties, TwentyThousandPointsInSeconds)
{
#if defined(__SANITIZE_ADDRESS__)
    const std::size_t n = 2000; // the sanitized build checks memory, not speed
#else
    const std::size_t n = 20000;
#endif
    std::mt19937 rng(16);
    for (bool integers : {true, false}) {
        const Points a = scan_like(rng, n, integers), b = scan_like(rng, n, integers);
        const auto start = std::chrono::steady_clock::now();
        const BottleneckResult bn = bottleneck_distance(a, b);
        const double bottleneck_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const WassersteinResult w = wasserstein_distance(a, b, 2);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_GT(bn.distance, 0.0);
        EXPECT_GE(w.distance, bn.distance);
        EXPECT_EQ(w.exact, integers);
        EXPECT_EQ(bottleneck_distance(b, a).distance, bn.distance);
        EXPECT_LT(seconds, 60.0);
        std::cout << "[   INFO   ] " << n << " " << (integers ? "integer" : "real") << " points: bottleneck "
                  << bn.distance << " (" << bn.decisions << " matchings, " << bottleneck_seconds << " s), W2 "
                  << w.distance << " (" << w.solves << " solves, " << w.arcs << " arcs), " << seconds << " s\n";
    }
}

} // namespace
} // namespace arbor::topology
