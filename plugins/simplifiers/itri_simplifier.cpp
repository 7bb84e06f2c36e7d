// itri_simplifier.cpp - the importance triangle (thesis §4.5.2): persistence,
// volume and hypervolume, each relative to the root, as a point in attribute
// space; importance is the area of the triangle its axis projections span.
// A branch must be strong in at least two measures to rank high, so small
// bright noise (persistence only) and faint broad swells (volume only) drop
// out before low-contrast but large structures such as a tumour.
#include "importance_area.hpp"
#include "simplifier_classes.hpp"

namespace arbor::simplifiers {

const arbor_plugin_descriptor kItriDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.simplifier.itri",
    ARBOR_KIND_SIMPLIFIER,
    "Importance triangle (ITri)",
    "1.0.0",
    "Arbor",
    "Ranks branches by the area of the triangle spanned by their relative persistence, volume and "
    "hypervolume: keeps structures that are strong in at least two of them.",
    "",
};

namespace {

class ItriSimplifier final : public sdk::Simplifier {
public:
    explicit ItriSimplifier(const arbor_host *host) : Simplifier(kItriDescriptor, host) {}

    void prepare(const arbor_measure_rows &schema) override
    {
        const sdk::MeasureColumns columns(schema);
        p_ = columns.find(ARBOR_MEASURE_PERSISTENCE);
        v_ = columns.find(ARBOR_MEASURE_VOLUME);
        hv_ = columns.find(ARBOR_MEASURE_HYPERVOLUME);
        width_ = schema.measure_count;
    }

    void importance(const arbor_measure_rows &rows, double *out) override
    {
        if (width_ == 0 || rows.measure_count != width_)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "rows do not have the columns given to prepare");
        for (uint32_t r = 0; r < rows.row_count; ++r) {
            const double *m = rows.relative_measures + std::size_t{r} * width_;
            out[r] = importance_triangle(m[p_], m[v_], m[hv_]);
        }
    }

private:
    uint32_t p_ = 0, v_ = 0, hv_ = 0, width_ = 0;
};

} // namespace

sdk::Instance *create_itri(const arbor_host *host)
{
    return new ItriSimplifier(host);
}

} // namespace arbor::simplifiers
