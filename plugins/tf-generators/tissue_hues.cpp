#include "tissue_hues.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace arbor::tf {

namespace {

constexpr double kBonePeakHu = 700.0;

enum Family : std::size_t { kLung, kFat, kSoftTissue, kContrast, kBone };

// The family of a mean in HU: the bins of the usual landmarks (air and lung
// below -200, fat to -20, soft tissue and blood to 120, iodinated contrast
// to 350, bone above).
std::size_t family_of_mean(double hu)
{
    if (hu < -200)
        return kLung;
    if (hu < -20)
        return kFat;
    if (hu < 120)
        return kSoftTissue;
    if (hu < 350)
        return kContrast;
    return kBone;
}

std::string format_hu(const char *what, double hu)
{
    char text[48];
    std::snprintf(text, sizeof text, "%s %.0f HU", what, hu);
    return text;
}

} // namespace

const std::vector<HueFamily> &hue_families()
{
    static const std::vector<HueFamily> families = {
        {"lung and airways", 210.0, 20.0, 62.0, 80.0, 0.12, 0.30},
        {"fat", 50.0, 12.0, 80.0, 90.0, 0.45, 0.70},
        {"soft tissue", 12.0, 14.0, 60.0, 76.0, 0.28, 0.50},
        {"contrast", 358.0, 12.0, 42.0, 56.0, 0.75, 1.00},
        {"bone", 44.0, 10.0, 86.0, 96.0, 0.06, 0.18},
    };
    return families;
}

bool holds_hounsfield_units(const arbor_tf_request &request, std::string *why)
{
    const arbor_volume *v = request.volume;
    if (!v || !ARBOR_HAS_FIELD(arbor_volume, v->struct_size, value_unit) || !std::isfinite(v->value_scale) ||
        v->value_scale == 0 || !std::isfinite(v->value_offset))
        return false;
    const std::string unit = v->value_unit ? v->value_unit : "";
    if (unit == "HU") {
        if (why)
            *why = "values in HU";
        return true;
    }
    if (!unit.empty() || !ARBOR_HAS_FIELD(arbor_tf_request, request.struct_size, background_peak) ||
        !std::isfinite(request.background_peak))
        return false;
    const double air = request.background_peak * v->value_scale + v->value_offset;
    const double top = std::max(request.value_range[0], request.value_range[1]) * v->value_scale + v->value_offset;
    if (std::fabs(air + 1000.0) > 100.0 || top < 200.0)
        return false;
    if (why)
        *why = format_hu("no unit given; the air at", air) + ": taken as HU";
    return true;
}

std::vector<TissueChoice> choose_tissues(const sdk::BranchTreeView &tree, const arbor_tf_request &request)
{
    const uint32_t n = tree.size();
    const uint32_t volume = tree.require_column(ARBOR_MEASURE_VOLUME);
    const uint32_t hypervolume = tree.require_column(ARBOR_MEASURE_HYPERVOLUME);
    const double scale = request.volume->value_scale, offset = request.volume->value_offset;
    const auto hu = [&](double stored) { return stored * scale + offset; };
    std::string unit;
    holds_hounsfield_units(request, &unit);
    std::vector<TissueChoice> out(n);
    for (uint32_t b = 0; b < n; ++b) {
        TissueChoice &c = out[b];
        if (b == 0) {
            c.family = kSoftTissue;
            c.why = "the body as a whole, its skin; " + unit;
            continue;
        }
        const double voxels = tree.measure(b, volume);
        const double mean = voxels > 0 ? hu(request.value_range[0] + tree.measure(b, hypervolume) / voxels)
                                        : hu(tree.extremum_value(b));
        const double peak = hu(tree.extremum_value(b));
        c.family = family_of_mean(mean);
        c.why = format_hu("mean", mean);
        if (!tree.is_minimum(b) && peak >= kBonePeakHu && c.family != kBone) {
            c.family = kBone;
            c.why += ", " + format_hu("peak", peak);
        }
    }
    return out;
}

} // namespace arbor::tf
