#include "auto_denoise.hpp"

#include "core/cancelled.hpp"
#include "core/voxel_type.hpp"
#include "topology/critical_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace arbor::pipeline {

namespace {

constexpr double kNoiseDensity = 0.005; // extrema per voxel above which noise dominates
constexpr int64_t kBlock = 96;
constexpr double kStrengths[] = {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0}; // in smallest voxel spacings
constexpr double kMostVoxels = 2.0; // beyond, structures a few voxels across melt

// The middle of the volume, at most kBlock voxels a side, with its spacing.
Volume middle_block(const Volume &v)
{
    const Geometry &g = v.geometry();
    Geometry b = g;
    std::array<int64_t, 3> start{};
    for (int a = 0; a < 3; ++a) {
        b.dims[a] = std::min(g.dims[a], kBlock);
        start[a] = (g.dims[a] - b.dims[a]) / 2;
    }
    Volume out = Volume::allocate(v.type(), b, v.mapping(), uint64_t{1} << 32);
    const std::size_t size = arbor_voxel_size(v.type());
    const auto *src = static_cast<const char *>(v.data());
    auto *dst = static_cast<char *>(out.data());
    for (int64_t k = 0; k < b.dims[2]; ++k)
        for (int64_t j = 0; j < b.dims[1]; ++j) {
            const int64_t from = start[0] + g.dims[0] * ((start[1] + j) + g.dims[1] * (start[2] + k));
            std::memcpy(dst + static_cast<std::size_t>(b.dims[0] * (j + b.dims[1] * k)) * size,
                        src + static_cast<std::size_t>(from) * size, static_cast<std::size_t>(b.dims[0]) * size);
        }
    return out;
}

uint64_t branches_of(const Volume &v)
{
    const Geometry &g = v.geometry();
    return topology::count_extrema(v.type(), v.data(), g.dims[0], g.dims[1], g.dims[2]).branches();
}

} // namespace

std::optional<std::size_t> find_plateau(const std::vector<uint64_t> &branches)
{
    std::vector<double> drop;
    for (std::size_t i = 0; i + 1 < branches.size(); ++i)
        drop.push_back(std::log(std::max<double>(static_cast<double>(branches[i]), 1)) -
                       std::log(std::max<double>(static_cast<double>(branches[i + 1]), 1)));
    if (drop.empty())
        return std::nullopt;
    // Only after the steepest step: a weak start that changes nothing yet is
    // not a plateau.
    const std::size_t steepest = static_cast<std::size_t>(std::max_element(drop.begin(), drop.end()) - drop.begin());
    for (std::size_t i = steepest + 1; i < drop.size(); ++i)
        if (drop[i] < 0.2 * drop[steepest])
            return i;
    return std::nullopt;
}

std::size_t plateau_index(const std::vector<uint64_t> &branches)
{
    return find_plateau(branches).value_or(branches.empty() ? 0 : branches.size() - 1);
}

DenoiseAdvice advise_denoising(const Volume &volume, const GaussianFn &gaussian, std::stop_token stop)
{
    DenoiseAdvice a;
    const Volume block = middle_block(volume);
    a.block = std::max({block.geometry().dims[0], block.geometry().dims[1], block.geometry().dims[2]});
    const uint64_t raw = branches_of(block);
    a.extremum_density = static_cast<double>(raw + 1) / static_cast<double>(block.voxel_count());
    a.noise_dominated = a.extremum_density > kNoiseDensity;
    if (!a.noise_dominated)
        return a;
    const auto &sp = volume.geometry().spacing;
    const double unit = std::min({sp[0], sp[1], sp[2]});
    std::vector<uint64_t> counts;
    for (const double s : kStrengths) {
        throw_if_stopped(stop);
        const uint64_t n = s == 0.0 ? raw : branches_of(gaussian(block, s * unit));
        a.study.push_back({s * unit, n});
        counts.push_back(n);
    }
    a.sigma_mm = std::min(a.study[plateau_index(counts)].sigma_mm, kMostVoxels * unit);
    return a;
}

std::string DenoiseAdvice::describe() const
{
    std::ostringstream s;
    s.precision(3);
    s << 100.0 * extremum_density << " % of the voxels of a " << block << "^3 block are extrema";
    if (!noise_dominated)
        return s.str() + ": not dominated by noise, not denoised";
    s << ": noise; Gaussian sigma " << sigma_mm << " mm, the plateau of a study there (";
    for (std::size_t i = 0; i < study.size(); ++i)
        s << (i ? ", " : "") << study[i].sigma_mm << " mm: " << study[i].branches;
    s << " branches)";
    return s.str();
}

} // namespace arbor::pipeline
