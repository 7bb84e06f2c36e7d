// auto_denoise.hpp - denoising chosen the way `arbor denoise-study` would
// suggest, cheaply enough to be the default.
//
// A scan is dominated by noise when its field has many extrema: more than
// one voxel in 200 (a smooth scan has a few thousand in millions).  Then the
// study runs on a block from the middle of the volume (at most 96 voxels a
// side): Gaussian smoothing from 0 to 3 times the smallest voxel spacing in
// steps of a half, the branch count at each from its extrema (no contour
// tree needed, topology/critical_points.hpp), and the strength chosen is the
// study's plateau: the first after the steepest step whose next step removes
// less than a fifth (in log terms) of what the steepest removed - noise gone, structures
// not yet melting - but never more than two voxel spacings, beyond which
// structures a few voxels across (a small tumour) melt.
#pragma once

#include "core/volume.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

namespace arbor::pipeline {

struct DenoiseAdvice {
    double extremum_density = 0.0; // extrema per voxel of the unfiltered block
    bool noise_dominated = false;
    int64_t block = 0; // voxels a side of the block studied
    struct Step {
        double sigma_mm = 0.0;
        uint64_t branches = 0;
    };
    std::vector<Step> study; // empty when the scan is not noise-dominated
    double sigma_mm = 0.0;   // chosen; 0: leave the scan as it is
    std::string describe() const;
};

// Smooths `volume` with a Gaussian of `sigma_mm`.
using GaussianFn = std::function<Volume(const Volume &volume, double sigma_mm)>;

DenoiseAdvice advise_denoising(const Volume &volume, const GaussianFn &gaussian, std::stop_token stop = {});

// The plateau of a study over branch counts at increasing strengths (what
// `arbor denoise-study` marks): after the steepest step, the first point
// whose next step removes less than a fifth (in log terms) of what the
// steepest removed.  None when every later step still removes more: the
// tree is still shrinking fast at the range's end.
std::optional<std::size_t> find_plateau(const std::vector<uint64_t> &branches);
// The plateau, else the study's last strength (automatic denoising).
std::size_t plateau_index(const std::vector<uint64_t> &branches);

} // namespace arbor::pipeline
