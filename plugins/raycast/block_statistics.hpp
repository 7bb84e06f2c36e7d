// block_statistics.hpp - what each 8^3 block of the volume holds, whatever
// the transfer functions: its value range and the labels its samples can
// take (each with the block's one-voxel apron, everything a trilinear
// sample inside the block reads; with the labels' tree, also the labels
// on the paths between them, which samples in mixed cells resolve to).  Built once per volume and labels revision, on all
// cores; a new set of transfer functions then finds the empty blocks in
// O(blocks), not O(voxels).
#pragma once

#include "voxel_grid.hpp"

#include <cstdint>
#include <vector>

namespace arbor::raycast {

class BlockStatistics {
public:
    static constexpr int64_t kBlock = 8;
    // More labels than this in one block: it is never skipped (rare: a
    // block where many small structures meet).
    static constexpr uint32_t kMaxLabels = 16;

    void build(const VoxelGrid &g, const sdk::Task &task);

    int64_t bx() const { return bx_; }
    int64_t by() const { return by_; }
    int64_t bz() const { return bz_; }
    std::size_t count() const { return lo_.size(); }
    float low(std::size_t b) const { return lo_[b]; }
    float high(std::size_t b) const { return hi_[b]; }
    // The labels present in block b; `many` when more than kMaxLabels.
    bool many(std::size_t b) const { return label_count_[b] > kMaxLabels; }
    const uint32_t *labels(std::size_t b) const { return &labels_[b * kMaxLabels]; }
    uint32_t label_count(std::size_t b) const { return label_count_[b]; }

private:
    int64_t bx_ = 0, by_ = 0, bz_ = 0;
    std::vector<float> lo_, hi_;
    std::vector<uint32_t> labels_;     // kMaxLabels per block
    std::vector<uint32_t> label_count_; // kMaxLabels + 1: many
};

} // namespace arbor::raycast
