// tf_generation.hpp - running depictors and transfer-function generators on
// a branch tree: host-owned output records (pre-filled as the SDK says),
// the plugin call, and a check of what came back.  A plugin returning
// out-of-range values is refused with a PluginError naming it.
#pragma once

#include "plugin_instance.hpp"

#include <arbor/depictor.h>
#include <arbor/transfer_function.h>

#include <memory>
#include <string>
#include <vector>

namespace arbor {

class DepictionRecord {
public:
    explicit DepictionRecord(uint32_t branches); // neutral: role OTHER, factors 1, hue NaN, saturation 1
    DepictionRecord(const DepictionRecord &) = delete;
    DepictionRecord &operator=(const DepictionRecord &) = delete;
    arbor_depiction &record() { return record_; }
    const arbor_depiction &record() const { return record_; }

private:
    std::vector<arbor_branch_role> role_;
    std::vector<float> at_saddle_, at_extremum_, hue_, saturation_;
    arbor_depiction record_{};
};

// Per-branch transfer functions with host-owned arrays (control points
// copied out of the call's task memory).
class TransferFunctions {
public:
    static constexpr uint32_t kNoteSize = 160;
    TransferFunctions(uint32_t branches, uint32_t lut_size, double opacity_unit_distance);
    TransferFunctions(const TransferFunctions &) = delete;
    TransferFunctions &operator=(const TransferFunctions &) = delete;
    arbor_tf_set &record() { return record_; }
    const arbor_tf_set &record() const { return record_; }
    uint32_t branch_count() const { return record_.branch_count; }
    uint32_t lut_size() const { return record_.lut_size; }
    const float *lut(uint32_t b) const { return lut_.data() + std::size_t{b} * record_.lut_size * 4; }
    std::pair<double, double> domain(uint32_t b) const { return {domain_[2 * b], domain_[2 * b + 1]}; }
    const std::vector<uint32_t> &point_offsets() const { return offsets_; }
    const std::vector<arbor_tf_point> &points() const { return points_; }
    // What the generator said about branch b ("" when nothing).
    std::string note(uint32_t b) const;

    // Filling from a file: branch b's domain and lut_size RGBA entries, then
    // the control points of every branch.
    void assign(uint32_t b, std::pair<double, double> domain, const float *rgba);
    void assign_points(std::vector<uint32_t> offsets, std::vector<arbor_tf_point> points);

    // A copy whose opacities are made thicker or thinner per branch: the
    // optical depth of branch b is multiplied by scale[b], alpha' = 1 - (1 - alpha)^scale[b]
    // (scale 2: as if the structure were twice as dense).
    std::unique_ptr<TransferFunctions> with_optical_depth(const std::vector<double> &scale) const;

private:
    friend void generate_transfer_functions(PluginInstance &, const arbor_tf_request &, TransferFunctions &,
                                            ProgressSink *, std::stop_token);
    std::vector<double> domain_;
    std::vector<float> lut_;
    std::vector<uint32_t> offsets_;
    std::vector<arbor_tf_point> points_;
    std::vector<char> notes_;
    arbor_tf_set record_{};
};

void depict(PluginInstance &depictor, const arbor_depiction_request &request, DepictionRecord &out,
            ProgressSink *progress = nullptr, std::stop_token stop = {});

void generate_transfer_functions(PluginInstance &generator, const arbor_tf_request &request, TransferFunctions &out,
                                 ProgressSink *progress = nullptr, std::stop_token stop = {});

} // namespace arbor
