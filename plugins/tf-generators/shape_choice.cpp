#include "shape_choice.hpp"

#include <cstdio>

namespace arbor::tf {

namespace {

std::string text(const char *format, double a, double b = 0)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, format, a, b);
    return buf;
}

} // namespace

ShapeChoice choose_shape(const sdk::BranchTreeView &tree, uint32_t b, double min_spacing)
{
    if (b == 0)
        return {OpacityShape::Ramp, "ramp: the root, the body as a whole"};
    const int thickness_col = tree.column(ARBOR_MEASURE_THICKNESS), compact_col = tree.column(ARBOR_MEASURE_COMPACTNESS);
    const double spacing = min_spacing > 0 ? min_spacing : 1.0;
    if (thickness_col >= 0 && compact_col >= 0) {
        const double t = tree.measure(b, static_cast<uint32_t>(thickness_col));
        const double c = tree.measure(b, static_cast<uint32_t>(compact_col));
        if (t > 0 && c < 0.2) {
            if (t < 1.5 * spacing)
                return {OpacityShape::Peak, text("peak: a thin sheet or shell, %.2g mm thick (%.2g voxels): its "
                                                 "isovalue",
                                                 t, t / spacing)};
            return {OpacityShape::Hat, text("hat: a thin sheet or shell, %.2g mm thick (compactness %.2f): its "
                                            "middle values",
                                            t, c)};
        }
    }
    const uint32_t p = tree.require_column(ARBOR_MEASURE_PERSISTENCE), v = tree.require_column(ARBOR_MEASURE_VOLUME),
                   rhv = tree.require_column(ARBOR_MEASURE_RELATIVE_HYPERVOLUME);
    const double pv = tree.measure(b, p) * tree.measure(b, v);
    const double phi = pv > 0 ? tree.measure(b, rhv) / pv : 1.0;
    const std::string thick =
        thickness_col >= 0 ? text("%.2g mm thick", tree.measure(b, static_cast<uint32_t>(thickness_col))) : "solid";
    if (phi >= 0.55)
        return {OpacityShape::Box, "box: " + thick + ", its values near the extremum (phi " + text("%.2f", phi) +
                                       "): all of it evenly"};
    if (phi >= 0.25)
        return {OpacityShape::Ramp,
                "ramp: " + thick + ", its values spread (phi " + text("%.2f", phi) + "): denser towards its core"};
    return {OpacityShape::InverseRamp,
            "inverse ramp: " + thick + ", its values near the saddle (phi " + text("%.2f", phi) + "): its bulk"};
}

} // namespace arbor::tf
