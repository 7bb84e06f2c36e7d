// histogram_generator.cpp - org.arbor.tf.histogram-ramp: the conventional
// baseline for comparison studies, what a user of a plain viewer gets.  One
// global 1D transfer function from the volume's histogram: opacity ramps
// from the first valley above the dominant (background) peak to the 99.5th
// percentile, colours follow a fixed black-red-yellow-white map of the value.
// Every branch gets that same function over its own interval, so equal
// values look the same whatever structure they belong to.
#include "tf_generator_classes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

namespace arbor::tf {

const arbor_plugin_descriptor kHistogramDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.tf.histogram-ramp",
    ARBOR_KIND_TF_GENERATOR,
    "Histogram ramp (baseline)",
    "1.0.0",
    "Arbor",
    "Baseline: one global transfer function from the histogram (opacity ramp above the background peak, a "
    "heat colour map), the same for every branch.",
    "",
};

namespace {

template <class T>
void count_values(const arbor_volume &v, double lo, double hi, std::vector<double> &bins)
{
    const char *base = static_cast<const char *>(v.voxels);
    const double scale = hi > lo ? (bins.size() - 1) / (hi - lo) : 0.0;
    for (int64_t k = 0; k < v.dims[2]; ++k)
        for (int64_t j = 0; j < v.dims[1]; ++j)
            for (int64_t i = 0; i < v.dims[0]; ++i) {
                T raw;
                std::memcpy(&raw, base + i * v.strides[0] + j * v.strides[1] + k * v.strides[2], sizeof raw);
                const double x = static_cast<double>(raw);
                const double at = std::clamp((x - lo) * scale, 0.0, static_cast<double>(bins.size() - 1));
                bins[static_cast<std::size_t>(at)] += 1.0;
            }
}

std::array<float, 3> heat(double u)
{
    u = std::clamp(u, 0.0, 1.0);
    return {static_cast<float>(std::min(1.0, 3 * u)), static_cast<float>(std::clamp(3 * u - 1, 0.0, 1.0)),
            static_cast<float>(std::clamp(3 * u - 2, 0.0, 1.0))};
}

class HistogramGenerator final : public sdk::TfGenerator {
public:
    explicit HistogramGenerator(const arbor_host *host)
        : TfGenerator(kHistogramDescriptor, host,
                      {sdk::ParamSpec::real("alpha-max", "Maximum opacity", 0.6, 0.0, 1.0)
                           .hint("Opacity at the top of the ramp"),
                       sdk::ParamSpec::integer("bins", "Histogram bins", 256, 16, 65536)})
    {
    }

    void generate(const arbor_tf_request &request, const sdk::BranchTreeView &tree, arbor_tf_set &out,
                  const sdk::Task &task) override
    {
        if (!request.volume || !request.volume->voxels)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the histogram baseline needs the volume");
        require_record(request.volume, "volume");
        const arbor_volume &v = *request.volume;
        const double lo = request.value_range[0], hi = request.value_range[1];
        std::vector<double> bins(static_cast<std::size_t>(params().integer("bins")), 0.0);
        switch (v.voxel_type) {
        case ARBOR_VOXEL_U8: count_values<uint8_t>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_I8: count_values<int8_t>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_U16: count_values<uint16_t>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_I16: count_values<int16_t>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_U32: count_values<uint32_t>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_I32: count_values<int32_t>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_F32: count_values<float>(v, lo, hi, bins); break;
        case ARBOR_VOXEL_F64: count_values<double>(v, lo, hi, bins); break;
        default: sdk::fail(ARBOR_ERROR_UNSUPPORTED, "unknown voxel type");
        }
        task.throw_if_cancelled();
        const auto value_of = [&](std::size_t bin) { return lo + (hi - lo) * bin / (bins.size() - 1.0); };
        // The dominant peak, then the first bin after it that is lower than both neighbours.
        const std::size_t peak = static_cast<std::size_t>(std::max_element(bins.begin(), bins.end()) - bins.begin());
        std::size_t valley = peak;
        while (valley + 1 < bins.size() && bins[valley + 1] <= bins[valley])
            ++valley;
        double total = 0.0, seen = 0.0;
        for (double c : bins)
            total += c;
        std::size_t top = bins.size() - 1;
        for (std::size_t b = 0; b < bins.size(); ++b) {
            seen += bins[b];
            if (seen >= 0.995 * total) {
                top = b;
                break;
            }
        }
        const double ramp_lo = value_of(valley), ramp_hi = std::max(value_of(top), ramp_lo + (hi - lo) * 1e-6);
        const double alpha_max = params().number("alpha-max");
        const auto rgba = [&](double value) {
            const std::array<float, 3> c = heat(hi > lo ? (value - lo) / (hi - lo) : 1.0);
            const double a = alpha_max * std::clamp((value - ramp_lo) / (ramp_hi - ramp_lo), 0.0, 1.0);
            return std::array<float, 4>{c[0], c[1], c[2], static_cast<float>(a)};
        };
        const uint32_t n = tree.size();
        auto *points = static_cast<arbor_tf_point *>(task.allocate(sizeof(arbor_tf_point) * 4 * n));
        for (uint32_t b = 0; b < n; ++b) {
            const auto domain = branch_domain(tree, request, b);
            bake_lut(out, b, domain, rgba);
            out.point_offsets[b] = 4 * b;
            const double at[4] = {domain.first, std::clamp(ramp_lo, domain.first, domain.second),
                                  std::clamp(ramp_hi, domain.first, domain.second), domain.second};
            for (int i = 0; i < 4; ++i) {
                arbor_tf_point &p = points[4 * b + i];
                p.value = at[i];
                const auto c = rgba(at[i]);
                std::copy(c.begin(), c.end(), p.rgba);
            }
        }
        out.point_offsets[n] = 4 * n;
        out.points = points;
    }
};

} // namespace

sdk::Instance *create_histogram(const arbor_host *host)
{
    return new HistogramGenerator(host);
}

} // namespace arbor::tf
