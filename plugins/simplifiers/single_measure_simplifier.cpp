// single_measure_simplifier.cpp - persistence, volume and hypervolume: the
// importance of a branch is one of its measures relative to the root's (thesis
// §4.5.1), so thresholds mean the same on every volume.
#include "simplifier_classes.hpp"

namespace arbor::simplifiers {

namespace {

constexpr arbor_plugin_descriptor descriptor(const char *id, const char *name, const char *description)
{
    return {sizeof(arbor_plugin_descriptor), ARBOR_PLUGIN_FLAG_NONE, id, ARBOR_KIND_SIMPLIFIER, name, "1.0.0",
            "Arbor", description, ""};
}

class SingleMeasureSimplifier final : public sdk::Simplifier {
public:
    SingleMeasureSimplifier(const arbor_plugin_descriptor &d, const arbor_host *host, const char *measure)
        : Simplifier(d, host), measure_(measure)
    {
    }

    void prepare(const arbor_measure_rows &schema) override
    {
        column_ = sdk::MeasureColumns(schema).find(measure_);
        prepared_ = true;
    }

    void importance(const arbor_measure_rows &rows, double *out) override
    {
        if (!prepared_)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "importance called before prepare");
        if (column_ >= rows.measure_count)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "the rows have fewer columns than the schema");
        for (uint32_t r = 0; r < rows.row_count; ++r)
            out[r] = rows.relative_measures[std::size_t{r} * rows.measure_count + column_];
    }

private:
    const char *measure_;
    uint32_t column_ = 0;
    bool prepared_ = false;
};

} // namespace

const arbor_plugin_descriptor kPersistenceDescriptor =
    descriptor("org.arbor.simplifier.persistence", "Persistence",
               "Ranks branches by relative persistence: the value range between extremum and saddle, over the "
               "volume's full range. Keeps high-contrast features however small.");
const arbor_plugin_descriptor kVolumeDescriptor =
    descriptor("org.arbor.simplifier.volume", "Volume",
               "Ranks branches by relative volume: the voxels of the region each branch encloses, over all "
               "voxels. Keeps large features however faint.");
const arbor_plugin_descriptor kHypervolumeDescriptor =
    descriptor("org.arbor.simplifier.hypervolume", "Hypervolume",
               "Ranks branches by relative hypervolume: the sum of (value - global minimum) over each "
               "branch's region, over the whole volume's.");

sdk::Instance *create_persistence(const arbor_host *host)
{
    return new SingleMeasureSimplifier(kPersistenceDescriptor, host, ARBOR_MEASURE_PERSISTENCE);
}
sdk::Instance *create_volume(const arbor_host *host)
{
    return new SingleMeasureSimplifier(kVolumeDescriptor, host, ARBOR_MEASURE_VOLUME);
}
sdk::Instance *create_hypervolume(const arbor_host *host)
{
    return new SingleMeasureSimplifier(kHypervolumeDescriptor, host, ARBOR_MEASURE_HYPERVOLUME);
}

} // namespace arbor::simplifiers
