#include "bottleneck_distance.hpp"

#include "bottleneck_matching.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace arbor::topology {

namespace {

// Candidates listed once they are this few (8 bytes each).
constexpr uint64_t kListable = uint64_t{1} << 21;
// Candidates drawn to choose a pivot: the median of the sample.
constexpr int kSample = 15;

// |p - q| exactly as linf_distance computes it.
double difference(double p, double q)
{
    return p > q ? p - q : q - p;
}

// The candidate values in an open interval (lo, hi): |p - q| for p in one
// diagram's births (deaths) and q in the other's, and every half persistence.
// For a fixed p the q with |p - q| < t form a run of the sorted q around p
// (the rounded difference is monotone in q on each side), found by binary
// search, so counting costs O(n log n) and listing is proportional to the
// output.
class Candidates {
public:
    Candidates(std::span<const PlanePoint> a, std::span<const PlanePoint> b)
    {
        for (const PlanePoint &p : a) {
            axes_[0].p.push_back(p.x);
            axes_[1].p.push_back(p.y);
            halves_.push_back(BottleneckMatching::half_persistence(p));
        }
        for (const PlanePoint &q : b) {
            axes_[0].q.push_back(q.x);
            axes_[1].q.push_back(q.y);
            halves_.push_back(BottleneckMatching::half_persistence(q));
        }
        for (Axis &axis : axes_)
            std::sort(axis.q.begin(), axis.q.end());
        std::sort(halves_.begin(), halves_.end());
    }

    double largest_half() const { return halves_.empty() ? 0.0 : halves_.back(); }

    uint64_t count(double lo, double hi) const
    {
        uint64_t n = 0;
        for (const Axis &axis : axes_)
            for (double p : axis.p) {
                const Runs r = runs(axis.q, p, lo, hi);
                n += (r.inner_first - r.outer_first) + (r.outer_last - r.inner_last);
            }
        return n + halves_in(lo, hi).second - halves_in(lo, hi).first;
    }

    // The candidate of the given rank among those in (lo, hi), in the order
    // count() walks them.
    double select(uint64_t rank, double lo, double hi) const
    {
        for (const Axis &axis : axes_)
            for (double p : axis.p) {
                const Runs r = runs(axis.q, p, lo, hi);
                const uint64_t left = r.inner_first - r.outer_first, right = r.outer_last - r.inner_last;
                if (rank < left)
                    return difference(p, axis.q[r.outer_first + rank]);
                if (rank < left + right)
                    return difference(p, axis.q[r.inner_last + (rank - left)]);
                rank -= left + right;
            }
        return halves_[halves_in(lo, hi).first + rank];
    }

    void list(double lo, double hi, std::vector<double> &out) const
    {
        for (const Axis &axis : axes_)
            for (double p : axis.p) {
                const Runs r = runs(axis.q, p, lo, hi);
                for (std::size_t i = r.outer_first; i < r.inner_first; ++i)
                    out.push_back(difference(p, axis.q[i]));
                for (std::size_t i = r.inner_last; i < r.outer_last; ++i)
                    out.push_back(difference(p, axis.q[i]));
            }
        const auto [first, last] = halves_in(lo, hi);
        out.insert(out.end(), halves_.begin() + static_cast<std::ptrdiff_t>(first),
                   halves_.begin() + static_cast<std::ptrdiff_t>(last));
    }

private:
    struct Axis {
        std::vector<double> p, q; // q sorted
    };
    // [outer_first, outer_last): |p - q| < hi; [inner_first, inner_last) inside
    // it: |p - q| <= lo.  The candidates are the two runs between them.
    struct Runs {
        std::size_t outer_first, inner_first, inner_last, outer_last;
    };

    // [first, last) of the sorted q with |p - q| < t (strict) or <= t.
    static std::pair<std::size_t, std::size_t> near(const std::vector<double> &q, double p, double t, bool strict)
    {
        const auto close = [&](double d) { return strict ? d < t : d <= t; };
        const auto first = std::partition_point(q.begin(), q.end(), [&](double x) { return x < p && !close(p - x); });
        const auto last = std::partition_point(first, q.end(), [&](double x) { return x < p || close(x - p); });
        return {static_cast<std::size_t>(first - q.begin()), static_cast<std::size_t>(last - q.begin())};
    }

    static Runs runs(const std::vector<double> &q, double p, double lo, double hi)
    {
        const auto outer = near(q, p, hi, true);
        if (lo < 0.0)
            return {outer.first, outer.first, outer.first, outer.second};
        const auto inner = near(q, p, lo, false);
        return {outer.first, std::max(inner.first, outer.first), std::min(inner.second, outer.second),
                outer.second};
    }

    std::pair<std::size_t, std::size_t> halves_in(double lo, double hi) const
    {
        const auto first = std::upper_bound(halves_.begin(), halves_.end(), lo);
        const auto last = std::lower_bound(first, halves_.end(), hi);
        return {static_cast<std::size_t>(first - halves_.begin()), static_cast<std::size_t>(last - halves_.begin())};
    }

    Axis axes_[2];
    std::vector<double> halves_; // sorted
};

std::vector<PlanePoint> off_diagonal(std::span<const PlanePoint> points)
{
    std::vector<PlanePoint> out;
    out.reserve(points.size());
    for (const PlanePoint &p : points)
        if (p.y != p.x)
            out.push_back(p);
    return out;
}

} // namespace

BottleneckResult bottleneck_distance(std::span<const PlanePoint> a_in, std::span<const PlanePoint> b_in)
{
    // Points on the diagonal go to it at no cost and take nothing from
    // anyone: leaving them out changes no distance.
    const std::vector<PlanePoint> a = off_diagonal(a_in), b = off_diagonal(b_in);
    BottleneckResult result;
    if (a.empty() && b.empty())
        return result;
    const Candidates candidates(a, b);
    BottleneckMatching matching(a, b);
    // Invariant: every candidate <= lo is infeasible, hi is feasible (all
    // points to the diagonal costs the largest half persistence).
    double lo = -1.0, hi = candidates.largest_half();
    std::mt19937_64 random(0x5eed);
    for (;;) {
        const uint64_t n = candidates.count(lo, hi);
        if (n == 0)
            break;
        if (n <= kListable) {
            std::vector<double> values;
            values.reserve(n);
            candidates.list(lo, hi, values);
            std::sort(values.begin(), values.end());
            values.erase(std::unique(values.begin(), values.end()), values.end());
            std::size_t first = 0, last = values.size(); // the answer: values[first] or hi
            while (first < last) {
                const std::size_t mid = first + (last - first) / 2;
                ++result.decisions;
                if (matching.perfect_at(values[mid]))
                    last = mid;
                else
                    first = mid + 1;
            }
            if (first < values.size())
                hi = values[first];
            break;
        }
        std::uniform_int_distribution<uint64_t> pick(0, n - 1);
        std::vector<double> sample(kSample);
        for (double &s : sample)
            s = candidates.select(pick(random), lo, hi);
        std::nth_element(sample.begin(), sample.begin() + kSample / 2, sample.end());
        const double pivot = sample[kSample / 2];
        ++result.decisions;
        if (matching.perfect_at(pivot))
            hi = pivot;
        else
            lo = pivot;
    }
    result.distance = hi;
    ++result.decisions;
    matching.perfect_at(hi);
    result.matched_pairs = matching.off_diagonal_pairs();
    return result;
}

} // namespace arbor::topology
