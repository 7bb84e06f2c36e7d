#include "classification.hpp"

#include <arbor/sdk/error.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace arbor::raycast {

void require_functions(const VoxelGrid &g, const arbor_tf_set &tf)
{
    if (g.max_label >= tf.branch_count)
        sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "label " + std::to_string(g.max_label) + " has no transfer function (" +
                                                    std::to_string(tf.branch_count) + " given)");
}

void ClassTable::build(const arbor_tf_set &tf, double step_mm)
{
    size_ = tf.lut_size;
    step_ = step_mm;
    range_.resize(tf.branch_count);
    rgba_.resize(static_cast<std::size_t>(tf.branch_count) * size_ * 4);
    const double exponent = step_mm / tf.opacity_unit_distance;
    for (uint32_t b = 0; b < tf.branch_count; ++b) {
        const double lo = tf.domain[2 * b], hi = tf.domain[2 * b + 1];
        range_[b] = {static_cast<float>(lo), hi > lo ? static_cast<float>((size_ - 1) / (hi - lo)) : 0.0f,
                     static_cast<float>(size_ - 1), 0.0f, 0.0f};
        for (uint32_t i = 0; i < size_; ++i) {
            const float *in = tf.lut + (static_cast<std::size_t>(b) * size_ + i) * 4;
            float *out = &rgba_[(static_cast<std::size_t>(b) * size_ + i) * 4];
            const double a = 1.0 - std::pow(1.0 - std::clamp(static_cast<double>(in[3]), 0.0, 1.0), exponent);
            for (int c = 0; c < 3; ++c)
                out[c] = static_cast<float>(std::clamp(static_cast<double>(in[c]), 0.0, 1.0) * a);
            out[3] = static_cast<float>(a);
        }
    }
    // Entry e is read for (value - low) * scale in [e - 0.5, e + 0.5), so
    // the entries that show are read within [first - 0.5, last + 0.5];
    // widened by a hundredth of an entry (lookup's float arithmetic is off
    // by far less), unbounded where the first or last entry shows (the
    // clamp reads them beyond).
    constexpr float kInfinity = std::numeric_limits<float>::infinity(), kMargin = 0.01f;
    for (uint32_t b = 0; b < tf.branch_count; ++b) {
        const float *rgba = &rgba_[static_cast<std::size_t>(b) * size_ * 4];
        uint32_t first = 0, end = size_;
        while (first < size_ && !(rgba[4 * first + 3] > 0.0f))
            ++first;
        while (end > first && !(rgba[4 * (end - 1) + 3] > 0.0f))
            --end;
        Range &r = range_[b];
        if (first == end) {
            r.shown_low = kInfinity, r.shown_high = -kInfinity;
        } else {
            r.shown_low = first == 0 ? -kInfinity : static_cast<float>(first) - 0.5f - kMargin;
            r.shown_high = end == size_ ? kInfinity : static_cast<float>(end - 1) + 0.5f + kMargin;
        }
    }
    // Level l holds the largest opacity of entries [i, i + 2^l).
    levels_ = static_cast<uint32_t>(std::bit_width(size_));
    max_alpha_.assign(static_cast<std::size_t>(tf.branch_count) * levels_ * size_, 0.0f);
    for (uint32_t b = 0; b < tf.branch_count; ++b) {
        float *level0 = &max_alpha_[static_cast<std::size_t>(b) * levels_ * size_];
        for (uint32_t i = 0; i < size_; ++i)
            level0[i] = rgba_[(static_cast<std::size_t>(b) * size_ + i) * 4 + 3];
        for (uint32_t l = 1; l < levels_; ++l) {
            const float *below = level0 + static_cast<std::size_t>(l - 1) * size_;
            float *row = level0 + static_cast<std::size_t>(l) * size_;
            const uint32_t half = 1u << (l - 1);
            for (uint32_t i = 0; i + (1u << l) <= size_; ++i)
                row[i] = std::max(below[i], below[i + half]);
        }
    }
}

float ClassTable::max_alpha(uint32_t label, float lo, float hi) const
{
    const Range &r = range_[label];
    const auto at = [&](float v) {
        const float x = (v - r.low) * r.scale;
        return static_cast<uint32_t>(std::clamp(x, 0.0f, r.last) + 0.5f);
    };
    const uint32_t a = std::min(at(lo), at(hi)), b = std::max(at(lo), at(hi));
    // Sparse table: the larger of the two power-of-two windows covering [a, b].
    const uint32_t level = static_cast<uint32_t>(std::bit_width(b - a + 1)) - 1;
    const float *row = &max_alpha_[(static_cast<std::size_t>(label) * levels_ + level) * size_];
    return std::max(row[a], row[b + 1 - (1u << level)]);
}

void BoundaryEmphasis::sample(const VoxelGrid &g)
{
    probes_.clear();
    if (g.surface.empty())
        return;
    const std::size_t n = g.value.size(), stride = std::max<std::size_t>(1, n / (1 << 18));
    probes_.reserve(n / stride + 1);
    for (std::size_t v = 0; v < n; v += stride)
        probes_.push_back({g.value[v], g.label.empty() ? 0u : g.label[v], g.surface[v].gradient});
}

void BoundaryEmphasis::build(const ClassTable &table, double strength)
{
    active_ = strength > 0 && !probes_.empty();
    factor_.fill(1.0f);
    if (!active_)
        return;
    std::array<double, 256> histogram{};
    double total = 0;
    for (const Probe &p : probes_)
        if (p.label < table.labels() && table.lookup(p.label, p.value)[3] > 0.0f) {
            histogram[p.gradient] += 1;
            total += 1;
        }
    std::size_t reference = 255;
    double seen = 0;
    for (std::size_t q = 0; q < 256 && total > 0; ++q) {
        seen += histogram[q];
        if (seen >= 0.85 * total) {
            reference = std::max<std::size_t>(q, 1);
            break;
        }
    }
    for (std::size_t q = 0; q < 256; ++q)
        factor_[q] = static_cast<float>(1.0 - strength + strength * std::min(1.0, static_cast<double>(q) / reference));
}

void Occupancy::build(const BlockStatistics &blocks, const ClassTable &table, const std::array<int64_t, 3> &dims,
                      double min_spacing)
{
    bx_ = blocks.bx();
    by_ = blocks.by();
    bz_ = blocks.bz();
    empty_.assign(blocks.count(), 0);
    const float transparent =
        static_cast<float>(1.0 - std::pow(1.0 - 1.0 / 1024.0, table.step() / (0.5 * min_spacing)));
    int64_t lo_block[3] = {bx_, by_, bz_}, hi_block[3] = {-1, -1, -1};
    for (int64_t bk = 0; bk < bz_; ++bk)
        for (int64_t bj = 0; bj < by_; ++bj)
            for (int64_t bi = 0; bi < bx_; ++bi) {
                const std::size_t b = static_cast<std::size_t>(bi + bx_ * (bj + by_ * bk));
                bool empty = !blocks.many(b);
                const uint32_t *labels = blocks.labels(b);
                for (uint32_t n = 0; empty && n < blocks.label_count(b); ++n)
                    empty = labels[n] >= table.labels() ||
                            table.max_alpha(labels[n], blocks.low(b), blocks.high(b)) < transparent;
                empty_[b] = empty ? 1 : 0;
                if (!empty) {
                    const int64_t at[3] = {bi, bj, bk};
                    for (int a = 0; a < 3; ++a) {
                        lo_block[a] = std::min(lo_block[a], at[a]);
                        hi_block[a] = std::max(hi_block[a], at[a]);
                    }
                }
            }
    for (int a = 0; a < 3; ++a) {
        low_[a] = static_cast<double>(std::max<int64_t>(lo_block[a] * kBlock - 1, 0));
        high_[a] = static_cast<double>(std::min<int64_t>((hi_block[a] + 1) * kBlock, dims[a] - 1));
    }
}

} // namespace arbor::raycast
