#include "background_level.hpp"

#include "voxel_type.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace arbor {

namespace {

constexpr std::size_t kBins = 1024;
constexpr double kLowPart = 0.4;      // where a background peak may lie
constexpr double kMinShare = 0.05;    // of the voxels, for a peak to be a background
constexpr double kTail = 0.05;        // of the peak's count: where its noise ends
constexpr double kStandOut = 5.0;     // a peak this many times the mean filled bin
constexpr uint64_t kSamples = 1 << 22; // enough for the histogram of any scan

} // namespace

std::optional<BackgroundLevel> estimate_background(const Volume &volume)
{
    const uint64_t n = static_cast<uint64_t>(volume.voxel_count());
    if (n == 0)
        return std::nullopt;
    const uint64_t stride = std::max<uint64_t>(1, n / kSamples);
    double lo = INFINITY, hi = -INFINITY;
    for (uint64_t v = 0; v < n; v += stride) {
        const double x = volume.value(static_cast<int64_t>(v));
        if (std::isfinite(x)) {
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
    }
    if (!(hi > lo))
        return std::nullopt;
    std::vector<double> bins(kBins, 0.0);
    double total = 0;
    for (uint64_t v = 0; v < n; v += stride) {
        const double x = volume.value(static_cast<int64_t>(v));
        if (!std::isfinite(x))
            continue;
        bins[std::min(kBins - 1, static_cast<std::size_t>((x - lo) / (hi - lo) * kBins))] += 1;
        total += 1;
    }
    // Integer data leaves empty bins between its values: smooth over 5.
    std::vector<double> smooth(kBins, 0.0);
    for (std::size_t b = 0; b < kBins; ++b) {
        double s = 0;
        int c = 0;
        for (std::size_t k = b >= 2 ? b - 2 : 0; k <= std::min(kBins - 1, b + 2); ++k, ++c)
            s += bins[k];
        smooth[b] = s / c;
    }
    const std::size_t low_bins = static_cast<std::size_t>(kLowPart * kBins);
    const std::size_t peak = static_cast<std::size_t>(
        std::max_element(smooth.begin(), smooth.begin() + static_cast<std::ptrdiff_t>(low_bins)) - smooth.begin());
    // A background is a peak: it stands out of the histogram (a scan
    // cropped inside the body has a flat or tissue-shaped low end).
    double filled = 0, bins_filled = 0;
    for (const double c : smooth)
        if (c > 0) {
            filled += c;
            bins_filled += 1;
        }
    if (smooth[peak] < kStandOut * filled / bins_filled)
        return std::nullopt;
    // Down the peak's tail; a second peak as full within the low part (air
    // inside the field of view above the padding outside it) is background too.
    std::size_t end = peak;
    for (;;) {
        while (end + 1 < kBins && smooth[end] >= kTail * smooth[peak])
            ++end;
        std::size_t again = end;
        while (again < low_bins && smooth[again] < 0.5 * smooth[peak])
            ++again;
        if (again >= low_bins)
            break;
        end = again;
    }
    double below = 0;
    for (std::size_t b = 0; b <= end; ++b)
        below += bins[b];
    if (below < kMinShare * total || end >= low_bins)
        return std::nullopt;
    const auto value_of = [&](std::size_t b) { return lo + (hi - lo) * (static_cast<double>(b) + 0.5) / kBins; };
    BackgroundLevel out;
    out.peak = value_of(peak);
    out.level = value_of(end);
    out.fraction = below / total;
    return out;
}

} // namespace arbor
