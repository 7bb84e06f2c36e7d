// comparison.hpp - several simplifiers applied to one contour tree and what
// a comparison study reports about them: how much their kept sets overlap
// and, given ground-truth labels, how well their label maps match each
// ground-truth structure (Dice).
#pragma once

#include "pipeline/stage_results.hpp"

#include "core/volume.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace arbor::cli {

// One simplifier's decomposition and cut of the shared tree, as the
// pipeline computed them (the views point into `cut`).
struct SimplifiedTree {
    explicit SimplifiedTree(std::shared_ptr<const pipeline::CutResult> result)
        : cut_result(std::move(result)), id(cut_result->decomposition->simplifier.id),
          name(cut_result->decomposition->simplifier_name), version(cut_result->decomposition->simplifier.version),
          branches(cut_result->decomposition->branches), cut(cut_result->cut),
          seconds(cut_result->decomposition->seconds + cut_result->seconds)
    {
    }
    std::shared_ptr<const pipeline::CutResult> cut_result;
    std::string id, name, version;
    const topology::BranchDecomposition &branches;
    const topology::SimplificationCut &cut;
    double seconds;
};

struct ComparedSimplifier {
    ComparedSimplifier(std::shared_ptr<const pipeline::CutResult> cut, std::shared_ptr<const pipeline::LabelsResult> l)
        : run(std::move(cut)), labels_result(std::move(l)), labels(labels_result->labels)
    {
    }
    SimplifiedTree run;
    std::shared_ptr<const pipeline::LabelsResult> labels_result;
    const std::vector<uint32_t> &labels; // voxel -> kept label
};

// Kept sets compared structure by structure.  Different importances pick
// different representative extrema for one structure, so kept branches a
// (of run A) and b (of run B) are the same structure when each one's
// extremum lies in the other's labelled region.  The root, kept by all, is
// left out.
struct Overlap {
    std::size_t a = 0, b = 0; // indices into the compared simplifiers
    std::size_t shared = 0, only_a = 0, only_b = 0;
    double jaccard = 1.0; // shared / union (1 when both keep only the root)
};

std::vector<Overlap> kept_overlaps(const std::vector<ComparedSimplifier> &runs, const topology::ContourTree &tree);

// Per ground-truth label (non-zero), per simplifier: the kept label whose
// region best matches it and their Dice coefficient 2|T n S| / (|T| + |S|).
struct TruthMatch {
    uint32_t kept_label = 0;
    double dice = 0.0;
};
struct TruthScore {
    uint32_t truth_label = 0;
    uint64_t voxels = 0;
    std::vector<TruthMatch> best; // one per simplifier
};

// `truth` must have the volume's dims (throws std::invalid_argument
// otherwise); its values are read as integer labels.
std::vector<TruthScore> truth_scores(const Volume &truth, const std::vector<ComparedSimplifier> &runs);

} // namespace arbor::cli
