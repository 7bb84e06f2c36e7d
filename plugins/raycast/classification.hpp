// classification.hpp - post-classification tables and empty-space skipping.
// Each label's lookup table is corrected for the sample distance (opacity
// per unit distance -> per step) and premultiplied once per render; the
// occupancy grid marks 8^3 blocks whose samples can only be transparent, so
// rays jump over them.
#pragma once

#include "block_statistics.hpp"
#include "voxel_grid.hpp"

#include <arbor/transfer_function.h>

#include <algorithm>
#include <array>

namespace arbor::raycast {

// Throws (INVALID_ARGUMENT) when a label of the grid has no transfer function.
void require_functions(const VoxelGrid &g, const arbor_tf_set &tf);

class ClassTable {
public:
    // step_mm: the distance between samples along a ray.
    void build(const arbor_tf_set &tf, double step_mm);

    // Premultiplied RGBA of a sample of `value` in `label`.
    const float *lookup(uint32_t label, float value) const
    {
        return entry(label, (value - range_[label].low) * range_[label].scale);
    }
    // The same, or nullptr where the sample is certainly transparent: its
    // entry lies before the label's first entry of nonzero opacity or after
    // its last (and NaN).  Most samples in the blocks a ray does not skip
    // are transparent (64 % on walnut); for them, two comparisons replace
    // the clamp, the rounding and the load.
    const float *lookup_shown(uint32_t label, float value) const
    {
        const Range &r = range_[label];
        const float x = (value - r.low) * r.scale;
        return x >= r.shown_low && x <= r.shown_high ? entry(label, x) : nullptr;
    }
    // Largest opacity of `label` over values in [lo, hi].
    float max_alpha(uint32_t label, float lo, float hi) const;
    uint32_t labels() const { return static_cast<uint32_t>(range_.size()); }

    // The tables as lookup() reads them: entries per label, the
    // premultiplied RGBA rows (label after label), and each label's map
    // from value to entry, clamp((value - low) * scale, 0, last), rounded;
    // the entries of nonzero opacity are those of (value - low) * scale in
    // [shown_low, shown_high] (empty: low > high).
    struct Range {
        float low, scale, last;
        float shown_low, shown_high;
    };
    uint32_t entries() const { return size_; }
    double step() const { return step_; } // mm between the samples it is for
    const std::vector<float> &rgba() const { return rgba_; }
    const Range &range(uint32_t label) const { return range_[label]; }

private:
    const float *entry(uint32_t label, float x) const
    {
        x = std::min(std::max(0.0f, x), range_[label].last); // NaN: entry 0
        return &rgba_[(static_cast<std::size_t>(label) * size_ + static_cast<uint32_t>(x + 0.5f)) * 4];
    }

    uint32_t size_ = 0, levels_ = 0;
    double step_ = 1.0;
    std::vector<Range> range_;
    std::vector<float> rgba_;
    std::vector<float> max_alpha_; // per label and level: a sparse table of opacity maxima
};

// Opacity that emphasises boundaries, as clinical presets do: a sample's
// opacity is scaled by how steep the field is there, so homogeneous
// interiors thin out and structures read as surfaces.  The scale rises
// linearly from 1 - strength on flat ground to 1 at the reference
// steepness: the 85th percentile of the gradient magnitude over the voxels
// the transfer functions make visible at all (so it adapts to the data and
// to what is shown), 1 beyond.
class BoundaryEmphasis {
public:
    // Once per volume and labels: 2^18 voxels spread over the grid, kept
    // side by side, so build() for new transfer functions reads them in
    // order instead of missing the cache 2^18 times.
    void sample(const VoxelGrid &g);
    void build(const ClassTable &table, double strength);
    float factor(uint8_t gradient) const { return factor_[gradient]; }
    bool active() const { return active_; }
    const std::array<float, 256> &factors() const { return factor_; }

private:
    struct Probe {
        float value;
        uint32_t label;
        uint8_t gradient;
    };
    std::vector<Probe> probes_;
    std::array<float, 256> factor_{};
    bool active_ = false;
};

class Occupancy {
public:
    static constexpr int64_t kBlock = BlockStatistics::kBlock; // the ray caster divides by it with >> 3
    // O(blocks): from the value range and labels of each block.  A block
    // counts as transparent when its opacity stays under 1/1024 per half
    // voxel (of `min_spacing`), whatever the table's step: a finer step
    // must not skip more of a faint structure.
    void build(const BlockStatistics &blocks, const ClassTable &table, const std::array<int64_t, 3> &dims,
               double min_spacing);
    // True when every sample within block (bi, bj, bk) is transparent.
    bool empty(int64_t bi, int64_t bj, int64_t bk) const { return empty_[static_cast<std::size_t>(bi + bx_ * (bj + by_ * bk))]; }
    // Blocks along each axis and the flags, i fastest (1: empty).
    std::array<int64_t, 3> blocks() const { return {bx_, by_, bz_}; }
    const std::vector<uint8_t> &flags() const { return empty_; }
    // Voxel-index box around every non-empty block (lo > hi when all are
    // empty): rays are clipped to it before they start.
    const std::array<double, 3> &content_low() const { return low_; }
    const std::array<double, 3> &content_high() const { return high_; }

private:
    int64_t bx_ = 0, by_ = 0, bz_ = 0;
    std::vector<uint8_t> empty_;
    std::array<double, 3> low_{}, high_{};
};

} // namespace arbor::raycast
