#include "volume_statistics.hpp"

#include "voxel_type.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace arbor {

namespace {

template <class T>
void accumulate(const T *v, int64_t n, VolumeStatistics &s)
{
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    // Shifted sums keep the variance accurate for large offsets (CT in HU).
    double shift = 0.0;
    bool shifted = false;
    double sum = 0.0, sum2 = 0.0;
    for (int64_t i = 0; i < n; ++i) {
        const double x = static_cast<double>(v[i]);
        if constexpr (std::is_floating_point_v<T>) {
            if (std::isnan(x)) {
                if (s.first_non_finite < 0)
                    s.first_non_finite = i;
                ++s.nan_count;
                continue;
            }
            if (std::isinf(x)) {
                if (s.first_non_finite < 0)
                    s.first_non_finite = i;
                ++s.infinite_count;
                continue;
            }
        }
        if (!shifted) {
            shift = x;
            shifted = true;
        }
        lo = std::min(lo, x);
        hi = std::max(hi, x);
        const double d = x - shift;
        sum += d;
        sum2 += d * d;
        ++s.finite_count;
    }
    if (s.finite_count == 0)
        return;
    const double nf = static_cast<double>(s.finite_count);
    s.min = lo;
    s.max = hi;
    s.mean = shift + sum / nf;
    s.stddev = std::sqrt(std::max(0.0, sum2 / nf - (sum / nf) * (sum / nf)));
}

template <class T>
void fill_histogram(const T *v, int64_t n, VolumeStatistics &s)
{
    const std::size_t bins = s.histogram.size();
    const double range = s.max - s.min;
    s.bin_width = range > 0 ? range / static_cast<double>(bins) : 1.0;
    const double scale = range > 0 ? static_cast<double>(bins) / range : 0.0;
    for (int64_t i = 0; i < n; ++i) {
        const double x = static_cast<double>(v[i]);
        if constexpr (std::is_floating_point_v<T>)
            if (!std::isfinite(x))
                continue;
        std::size_t b = static_cast<std::size_t>((x - s.min) * scale);
        if (b >= bins)
            b = bins - 1;
        ++s.histogram[b];
    }
}

} // namespace

VolumeStatistics compute_statistics(const Volume &volume, int bins)
{
    VolumeStatistics s;
    s.histogram.assign(static_cast<std::size_t>(std::max(1, bins)), 0);
    dispatch_voxel_type(volume.type(), [&](auto t) {
        using T = decltype(t);
        accumulate(volume.as<T>(), volume.voxel_count(), s);
        if (s.finite_count > 0)
            fill_histogram(volume.as<T>(), volume.voxel_count(), s);
    });
    return s;
}

double VolumeStatistics::quantile(double fraction) const
{
    if (finite_count == 0)
        return 0.0;
    const double target = fraction * static_cast<double>(finite_count);
    double seen = 0.0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        seen += static_cast<double>(histogram[b]);
        if (seen >= target)
            return std::min(max, bin_low(b + 1));
    }
    return max;
}

double VolumeStatistics::mode() const
{
    if (histogram.empty())
        return 0.0;
    const auto it = std::max_element(histogram.begin(), histogram.end());
    return bin_low(static_cast<std::size_t>(it - histogram.begin()));
}

} // namespace arbor
