// region_scores.hpp - how well the regions a simplification keeps match the
// structures of a ground truth.
//
// The voxels are counted once into a contingency table (kept region x truth
// label); every score follows from it: Dice 2|T n S| / (|T| + |S|),
// precision |T n S| / |S| and recall |T n S| / |T|.  Two matchings are
// reported.  The best match pairs each truth structure with the region of
// highest Dice, so one region may be credited for several structures (an
// under-segmentation scores well).  The one-to-one match (the assignment
// maximising the total Dice) credits each region at most once.
//
// A kept branch's region is its exclusive region (the voxels labelled with
// it) or, scored as a subtree, that region together with the regions of
// every kept branch below it in the simplified hierarchy.
#pragma once

#include "core/volume.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace arbor::study {

// A ground-truth label map: every voxel holds a non-negative integer, 0 for
// no structure.
struct TruthLabels {
    std::vector<uint32_t> labels; // the distinct non-zero labels, ascending
    std::vector<uint64_t> voxels; // per label
    std::vector<uint32_t> index;  // per voxel: 0 for none, i + 1 for labels[i]
};

// Throws std::invalid_argument when a voxel is not a non-negative integer
// or there are more than `max_labels` distinct labels.
TruthLabels read_truth(const Volume &truth, std::size_t max_labels = 10000);

// Voxels per (kept region, truth label): rows are the kept labels, columns
// 0 (no truth structure) and 1..T (truth.labels).
struct Contingency {
    std::size_t regions = 0, truths = 0;
    std::vector<uint64_t> count; // regions x (truths + 1), row-major

    uint64_t at(std::size_t region, std::size_t column) const { return count[region * (truths + 1) + column]; }
    uint64_t region_voxels(std::size_t region) const;
};

// `kept_labels` holds per voxel its kept label (< regions); throws
// std::invalid_argument when sizes or labels do not fit.
Contingency count_overlaps(const TruthLabels &truth, std::span<const uint32_t> kept_labels, std::size_t regions);

// Each region together with every region below it: `kept_parent[k]` is the
// nearest kept ancestor of region k (-1 for the root).
Contingency subtree_regions(const Contingency &exclusive, const std::vector<int32_t> &kept_parent);

struct RegionMatch {
    long region = -1; // the kept label; -1: none
    uint64_t overlap = 0, region_voxels = 0;
    double dice = 0.0, precision = 0.0, recall = 0.0;
};

struct TruthMatches {
    std::vector<RegionMatch> best;       // per truth label: the region of highest Dice
    std::vector<RegionMatch> one_to_one; // per truth label: its region in the assignment maximising total Dice
};

TruthMatches match_regions(const Contingency &table, const TruthLabels &truth);

} // namespace arbor::study
