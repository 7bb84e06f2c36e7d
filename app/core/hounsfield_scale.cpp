#include "hounsfield_scale.hpp"

#include "voxel_type.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace arbor {

namespace {

constexpr double kLow = -1200.0, kBin = 20.0;
constexpr int kBins = 70; // -1200 .. +200 HU
constexpr uint64_t kMaxSamples = uint64_t{1} << 22;

struct Tally {
    std::array<uint64_t, kBins> bins{};
    uint64_t samples = 0;

    void add(double hu)
    {
        ++samples;
        const double b = std::floor((hu - kLow) / kBin); // NaN compares false below
        if (b >= 0.0 && b < kBins)
            ++bins[static_cast<std::size_t>(b)];
    }

    static double centre(int b) { return kLow + kBin * (b + 0.5); }

    // The fullest bin among those whose centres lie in [lo, hi].
    int peak(double lo, double hi) const
    {
        int best = -1;
        for (int b = 0; b < kBins; ++b)
            if (centre(b) >= lo && centre(b) <= hi && (best < 0 || bins[b] > bins[best]))
                best = b;
        return best;
    }

    // Samples in the bins whose centres lie in [lo, hi], and how many bins.
    std::pair<uint64_t, int> mass(double lo, double hi) const
    {
        uint64_t sum = 0;
        int count = 0;
        for (int b = 0; b < kBins; ++b)
            if (centre(b) >= lo && centre(b) <= hi) {
                sum += bins[b];
                ++count;
            }
        return {sum, count};
    }
};

} // namespace

std::string HounsfieldEvidence::describe() const
{
    char text[160];
    std::snprintf(text, sizeof text, "%.0f %% air, peak at %.0f HU; %.0f %% soft tissue, peak at %.0f HU",
                  100.0 * air_fraction, air_peak, 100.0 * tissue_fraction, tissue_peak);
    return text;
}

std::optional<HounsfieldEvidence> infer_hounsfield(const Volume &volume)
{
    if (volume.empty() || volume.voxel_count() <= 0)
        return std::nullopt;
    const uint64_t n = static_cast<uint64_t>(volume.voxel_count());
    // An odd stride, so that the samples do not line up with rows or slices.
    const uint64_t stride = n <= kMaxSamples ? 1 : (n / kMaxSamples) | 1u;
    const ValueMapping &m = volume.mapping();
    Tally t;
    dispatch_voxel_type(volume.type(), [&](auto type) {
        using T = decltype(type);
        const T *v = static_cast<const T *>(volume.data());
        for (uint64_t i = 0; i < n; i += stride)
            t.add(m.physical(static_cast<double>(v[i])));
    });
    if (t.samples == 0)
        return std::nullopt;
    // Soft tissue must stand out as a peak, three times the mean bin
    // between air and it (where a chest's lung lies, broad and lower); a
    // phase map or any field spread evenly has no peak.
    const auto [gap_sum, gap_bins] = t.mass(-890.0, -310.0);
    const double gap = static_cast<double>(gap_sum) / gap_bins;
    const double total = static_cast<double>(t.samples);
    const int air = t.peak(-1050.0, -950.0), tissue = t.peak(-110.0, 90.0);
    HounsfieldEvidence e;
    e.air_peak = Tally::centre(air);
    e.tissue_peak = Tally::centre(tissue);
    e.air_fraction = static_cast<double>(t.mass(-1050.0, -950.0).first) / total;
    e.tissue_fraction = static_cast<double>(t.mass(-150.0, 150.0).first) / total;
    const bool air_peaks = e.air_fraction >= 0.01;
    const bool tissue_peaks = e.tissue_fraction >= 0.05 && static_cast<double>(t.bins[tissue]) >= 3.0 * gap &&
                              t.peak(-200.0, 200.0) == tissue;
    if (!air_peaks || !tissue_peaks)
        return std::nullopt;
    return e;
}

} // namespace arbor
