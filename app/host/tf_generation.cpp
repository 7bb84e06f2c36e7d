#include "tf_generation.hpp"

#include "depiction_application.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <string>

namespace arbor {

DepictionRecord::DepictionRecord(uint32_t branches)
    : role_(branches, ARBOR_ROLE_OTHER), at_saddle_(branches, 1.0f), at_extremum_(branches, 1.0f),
      hue_(branches, std::numeric_limits<float>::quiet_NaN()), saturation_(branches, 1.0f)
{
    record_.struct_size = sizeof record_;
    record_.branch_count = branches;
    record_.role = role_.data();
    record_.opacity_at_saddle = at_saddle_.data();
    record_.opacity_at_extremum = at_extremum_.data();
    record_.hue = hue_.data();
    record_.saturation = saturation_.data();
}

TransferFunctions::TransferFunctions(uint32_t branches, uint32_t lut_size, double opacity_unit_distance)
    : domain_(2 * std::size_t{branches}, 0.0), lut_(std::size_t{branches} * lut_size * 4, 0.0f),
      offsets_(std::size_t{branches} + 1, 0)
{
    record_.struct_size = sizeof record_;
    record_.branch_count = branches;
    record_.lut_size = lut_size;
    record_.opacity_unit_distance = opacity_unit_distance;
    record_.domain = domain_.data();
    record_.lut = lut_.data();
    record_.point_offsets = offsets_.data();
    notes_.assign(std::size_t{branches} * kNoteSize, '\0');
    record_.notes = notes_.data();
    record_.note_size = kNoteSize;
}

std::string TransferFunctions::note(uint32_t b) const
{
    if (b >= branch_count())
        return {};
    const char *n = notes_.data() + std::size_t{b} * kNoteSize;
    return std::string(n, strnlen(n, kNoteSize - 1));
}

void TransferFunctions::assign(uint32_t b, std::pair<double, double> domain, const float *rgba)
{
    domain_[2 * b] = domain.first;
    domain_[2 * b + 1] = domain.second;
    std::copy(rgba, rgba + std::size_t{record_.lut_size} * 4, lut_.begin() + std::size_t{b} * record_.lut_size * 4);
}

void TransferFunctions::assign_points(std::vector<uint32_t> offsets, std::vector<arbor_tf_point> points)
{
    offsets_ = std::move(offsets);
    points_ = std::move(points);
    record_.point_offsets = offsets_.data();
    record_.points = points_.data();
}

std::unique_ptr<TransferFunctions> TransferFunctions::with_optical_depth(const std::vector<double> &scale) const
{
    const auto thicker = [](float alpha, double m) {
        return static_cast<float>(1.0 - std::pow(1.0 - std::clamp(static_cast<double>(alpha), 0.0, 1.0), m));
    };
    auto out = std::make_unique<TransferFunctions>(branch_count(), lut_size(), record_.opacity_unit_distance);
    std::vector<float> lut(std::size_t{lut_size()} * 4);
    for (uint32_t b = 0; b < branch_count(); ++b) {
        const double m = b < scale.size() ? scale[b] : 1.0;
        std::copy(this->lut(b), this->lut(b) + lut.size(), lut.begin());
        for (std::size_t i = 3; i < lut.size(); i += 4)
            lut[i] = thicker(lut[i], m);
        out->assign(b, domain(b), lut.data());
    }
    std::vector<arbor_tf_point> points = points_;
    for (uint32_t b = 0; b < branch_count(); ++b)
        for (uint32_t i = offsets_[b]; i < offsets_[b + 1]; ++i)
            points[i].rgba[3] = thicker(points[i].rgba[3], b < scale.size() ? scale[b] : 1.0);
    out->assign_points(offsets_, std::move(points));
    out->notes_ = notes_;
    out->record_.notes = out->notes_.data();
    return out;
}

void depict(PluginInstance &depictor, const arbor_depiction_request &request, DepictionRecord &out,
            ProgressSink *progress, std::stop_token stop)
{
    const auto &table = depictor.interface<arbor_depictor_v1>(ARBOR_INTERFACE_DEPICTOR);
    Task task(progress, stop);
    depictor.check(depictor.call("depictor.depict", table.depict, &request, &out.record(), task.get()), "depicting the branches");
    const arbor_depiction &d = out.record();
    for (uint32_t b = 0; b < d.branch_count; ++b) {
        // Generators index tables by role: an unknown one must not reach them.
        if (d.role[b] > ARBOR_ROLE_DESCENDANT)
            throw PluginError(ARBOR_ERROR_OUT_OF_RANGE, depictor.id() + " returned role " + std::to_string(d.role[b]) +
                                                            " (no such role) for branch " + std::to_string(b));
        const float v[] = {d.opacity_at_saddle[b], d.opacity_at_extremum[b], d.saturation[b]};
        for (float x : v)
            if (!(x >= 0.0f && x <= 1.0f))
                throw PluginError(ARBOR_ERROR_OUT_OF_RANGE, depictor.id() + " returned a factor " + std::to_string(x) +
                                                                " outside [0, 1] for branch " + std::to_string(b));
        if (!std::isnan(d.hue[b]) && !(d.hue[b] >= 0.0f && d.hue[b] < 360.0f))
            throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                              depictor.id() + " returned hue " + std::to_string(d.hue[b]) + " for branch " +
                                  std::to_string(b));
    }
}

void generate_transfer_functions(PluginInstance &generator, const arbor_tf_request &request, TransferFunctions &out,
                                 ProgressSink *progress, std::stop_token stop)
{
    const auto &table = generator.interface<arbor_tf_generator_v1>(ARBOR_INTERFACE_TF_GENERATOR);
    Task task(progress, stop);
    arbor_tf_set &set = out.record();
    set.points = nullptr;
    set.depiction_by_host = 0;
    generator.check(generator.call("tf-generator.generate", table.generate, &request, &set, task.get()), "generating transfer functions");
    const auto refuse = [&](const std::string &what) {
        throw PluginError(ARBOR_ERROR_OUT_OF_RANGE, generator.id() + " returned " + what);
    };
    for (uint32_t b = 0; b < set.branch_count; ++b) {
        if (!std::isfinite(set.domain[2 * b]) || !std::isfinite(set.domain[2 * b + 1]) ||
            set.domain[2 * b] > set.domain[2 * b + 1])
            refuse("a domain that is not a finite interval for branch " + std::to_string(b));
        if (set.point_offsets[b + 1] < set.point_offsets[b])
            refuse("decreasing point offsets");
    }
    for (float x : out.lut_)
        if (!(x >= 0.0f && x <= 1.0f))
            refuse("a lookup-table value outside [0, 1]");
    const uint32_t points = set.point_offsets[set.branch_count];
    if (points > 0 && !set.points)
        refuse("point offsets counting points but no points");
    out.points_.assign(set.points, set.points + points);
    for (const arbor_tf_point &p : out.points_)
        for (float x : p.rgba)
            if (!(x >= 0.0f && x <= 1.0f) || !std::isfinite(p.value))
                refuse("a control point outside [0, 1] or at a non-finite value");
    for (uint32_t b = 0; b < set.branch_count; ++b)
        for (uint32_t i = set.point_offsets[b] + 1; i < set.point_offsets[b + 1]; ++i)
            if (out.points_[i].value < out.points_[i - 1].value)
                refuse("control points of branch " + std::to_string(b) + " out of value order (" +
                       std::to_string(out.points_[i - 1].value) + " before " + std::to_string(out.points_[i].value) +
                       "); points ascend in value");
    set.points = out.points_.data(); // the task's memory goes with the task
    // A generator that leaves the depiction to the host gets it applied here,
    // as depictor.h says, to the table and the points alike.
    if (set.depiction_by_host && request.depiction && request.tree)
        apply_depiction(*request.depiction, *request.tree, set, out.points_.data());
    for (uint32_t b = 0; b < set.branch_count; ++b)
        out.notes_[std::size_t{b + 1} * TransferFunctions::kNoteSize - 1] = '\0'; // a note ends in its slot
}

} // namespace arbor
