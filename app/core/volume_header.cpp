#include "volume_header.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace arbor {

uint64_t default_max_volume_bytes()
{
    if (const char *env = std::getenv("ARBOR_MAX_VOLUME_BYTES")) {
        char *end = nullptr;
        const unsigned long long v = std::strtoull(env, &end, 10);
        if (end && *end == '\0' && v > 0)
            return v;
    }
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page <= 0)
        return uint64_t{4} << 30;
    return static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) / 2;
}

std::string format_bytes(uint64_t bytes)
{
    static const char *units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
    double v = static_cast<double>(bytes);
    int u = 0;
    while (v >= 1000.0 && u < 6) {
        v /= 1000.0;
        ++u;
    }
    char buf[32];
    if (u == 0)
        std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
    else
        std::snprintf(buf, sizeof buf, "%.1f %s", v, units[u]);
    return buf;
}

std::string dims_text(const int64_t dims[3])
{
    return std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]);
}

std::string check_volume_header(const arbor_volume &h, uint64_t max_bytes)
{
    const uint32_t size = arbor_voxel_size(h.voxel_type);
    if (size == 0)
        return "unknown voxel type code " + std::to_string(h.voxel_type);
    for (int a = 0; a < 3; ++a)
        if (h.dims[a] <= 0)
            return "dimensions " + dims_text(h.dims) + ": every dimension must be at least 1";
    // Overflow-safe product: each factor is positive, compare by division.
    int64_t count = h.dims[0];
    for (int a = 1; a < 3; ++a) {
        if (h.dims[a] > kMaxVoxelCount / count)
            return "dimensions " + dims_text(h.dims) + " give more than " +
                   std::to_string(kMaxVoxelCount) + " voxels, the most Arbor handles";
        count *= h.dims[a];
    }
    if (count > kMaxVoxelCount)
        return "dimensions " + dims_text(h.dims) + " give more than " + std::to_string(kMaxVoxelCount) +
               " voxels, the most Arbor handles";
    const uint64_t bytes = static_cast<uint64_t>(count) * size;
    if (bytes > max_bytes)
        return "dimensions " + dims_text(h.dims) + " of " + arbor_voxel_type_name(h.voxel_type) +
               " voxels need " + format_bytes(bytes) + ", more than the " + format_bytes(max_bytes) +
               " this host allows for one volume (ARBOR_MAX_VOLUME_BYTES)";
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(h.spacing[a]) || h.spacing[a] <= 0.0)
            return "spacing " + std::to_string(h.spacing[0]) + " " + std::to_string(h.spacing[1]) +
                   " " + std::to_string(h.spacing[2]) + ": every spacing must be a positive number";
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(h.origin[a]))
            return "origin is not a finite position";
    for (int e = 0; e < 9; ++e)
        if (!std::isfinite(h.direction[e]))
            return "direction cosines are not finite";
    const double *d = h.direction;
    const double det = d[0] * (d[4] * d[8] - d[5] * d[7]) - d[1] * (d[3] * d[8] - d[5] * d[6]) +
                       d[2] * (d[3] * d[7] - d[4] * d[6]);
    if (std::fabs(det) < 1e-6)
        return "direction cosines are degenerate (the grid axes do not span space)";
    if (!std::isfinite(h.value_scale) || h.value_scale == 0.0 || !std::isfinite(h.value_offset))
        return "value mapping (scale " + std::to_string(h.value_scale) + ", offset " +
               std::to_string(h.value_offset) + ") is not usable";
    return "";
}

} // namespace arbor
