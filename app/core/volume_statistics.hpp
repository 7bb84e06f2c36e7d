// volume_statistics.hpp - value range, moments, non-finite samples and a
// histogram of a volume, in one pass (plus one for the histogram).
#pragma once

#include "volume.hpp"

#include <cstdint>
#include <vector>

namespace arbor {

struct VolumeStatistics {
    double min = 0.0;  // over finite samples, stored units
    double max = 0.0;
    double mean = 0.0;
    double stddev = 0.0;
    int64_t finite_count = 0;
    int64_t nan_count = 0;
    int64_t infinite_count = 0;
    int64_t first_non_finite = -1; // voxel index of the first NaN/inf, -1 if none
    // Histogram of finite samples over [min, max], equal-width bins.
    std::vector<int64_t> histogram;
    double bin_width = 0.0;

    double bin_low(std::size_t b) const { return min + bin_width * static_cast<double>(b); }
    // Value below which `fraction` of the finite samples lie (bin resolution).
    double quantile(double fraction) const;
    // Lower edge of the fullest bin.
    double mode() const;
};

VolumeStatistics compute_statistics(const Volume &volume, int bins = 64);

} // namespace arbor
