#include "matching_costs.hpp"

#include <algorithm>
#include <cmath>

namespace arbor::topology {

namespace {

// Largest coordinate of the exact scale: differences stay exact in double.
constexpr double kLargestExactCoordinate = 1099511627776.0; // 2^40

bool integral(double v)
{
    return std::floor(v) == v && std::fabs(v) <= kLargestExactCoordinate;
}

} // namespace

MatchingCosts::MatchingCosts(std::span<const PlanePoint> a, std::span<const PlanePoint> b, double p,
                             std::size_t nodes)
    : p_(p)
{
    if (std::floor(p) == p && p <= 64.0)
        integer_p_ = static_cast<int>(p);
    double max_half = 0.0;
    bool all_integral = true;
    for (const auto &side : {a, b})
        for (const PlanePoint &q : side) {
            max_half = std::max(max_half, (q.y - q.x) * 0.5);
            all_integral = all_integral && integral(q.x) && integral(q.y);
        }
    // The network simplex's potentials are sums of costs along a spanning
    // tree path (at most `nodes` arcs) on top of an artificial cost of 2^62:
    // arc costs up to 2^61 / nodes keep every sum below 2^63.
    const long double budget = std::ldexp(1.0L, 61) / static_cast<long double>(std::max<std::size_t>(nodes, 1));
    if (integer_p_ > 0 && all_integral) {
        long double largest = 1.0L; // (2 max_half)^p: the largest diagonal cost
        for (int i = 0; i < integer_p_; ++i)
            largest *= 2.0L * max_half;
        if (2.0L * largest + 1.0L <= budget) {
            exact_ = true;
            scale_ = std::ldexp(1.0L, integer_p_);
            saturated_ = 2.0L * largest + 1.0L;
            return;
        }
    }
    const long double largest = real(max_half);
    if (largest > 0.0L) {
        int exponent = 0;
        std::frexp(budget / (2.0L * largest), &exponent); // budget / (2 largest) in [2^(e-1), 2^e)
        scale_ = std::ldexp(1.0L, exponent - 1);
    }
    saturated_ = std::floor(scale_ * 2.0L * largest) + 1.0L;
}

long double MatchingCosts::real(double d) const
{
    if (integer_p_ > 0) {
        long double v = 1.0L;
        for (int i = 0; i < integer_p_; ++i)
            v *= d;
        return v;
    }
    return std::pow(static_cast<long double>(d), static_cast<long double>(p_));
}

int64_t MatchingCosts::of_distance(double d) const
{
    long double v;
    if (exact_) {
        v = 1.0L;
        const long double twice = 2.0L * d; // an integer
        for (int i = 0; i < integer_p_ && v < saturated_; ++i)
            v *= twice;
    } else {
        v = real(d) * scale_;
    }
    if (v >= saturated_)
        return static_cast<int64_t>(saturated_);
    return exact_ ? static_cast<int64_t>(v) : std::llround(v);
}

long double MatchingCosts::to_real(int64_t cost) const
{
    return static_cast<long double>(cost) / scale_;
}

} // namespace arbor::topology
