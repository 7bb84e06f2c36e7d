#include "simplifier_importance.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

namespace arbor {

namespace {

// The columns and per-row arrays behind the arbor_measure_rows records of one
// run, reused from one batch to the next.
struct MeasureTable {
    const char *ids[topology::kMeasureCount];
    std::vector<double> absolute, relative, saddle, extremum;
    std::vector<arbor_extremum_kind> kind;
    int32_t root_row = -1;
    ValueMapping mapping;

    explicit MeasureTable(ValueMapping m) : mapping(std::move(m))
    {
        for (int i = 0; i < topology::kMeasureCount; ++i)
            ids[i] = topology::measure_id(i);
    }

    void fill(const std::vector<topology::BranchMeasures> &rows)
    {
        const std::size_t width = topology::kMeasureCount;
        absolute.resize(rows.size() * width);
        relative.resize(rows.size() * width);
        saddle.resize(rows.size());
        extremum.resize(rows.size());
        kind.resize(rows.size());
        root_row = -1;
        for (std::size_t r = 0; r < rows.size(); ++r) {
            for (std::size_t c = 0; c < width; ++c) {
                absolute[r * width + c] = rows[r].absolute[c];
                relative[r * width + c] = rows[r].relative[c];
            }
            saddle[r] = rows[r].saddle_value;
            extremum[r] = rows[r].extremum_value;
            kind[r] = rows[r].kind == topology::BranchKind::Minimum ? ARBOR_EXTREMUM_MINIMUM : ARBOR_EXTREMUM_MAXIMUM;
            if (rows[r].kind == topology::BranchKind::Root)
                root_row = static_cast<int32_t>(r);
        }
    }

    arbor_measure_rows rows(uint32_t count) const
    {
        arbor_measure_rows r{};
        r.struct_size = sizeof r;
        r.row_count = count;
        r.measure_count = topology::kMeasureCount;
        r.measure_ids = ids;
        r.measures = count ? absolute.data() : nullptr;
        r.relative_measures = count ? relative.data() : nullptr;
        r.extremum_kind = count ? kind.data() : nullptr;
        r.saddle_value = count ? saddle.data() : nullptr;
        r.extremum_value = count ? extremum.data() : nullptr;
        r.root_row = count ? root_row : -1;
        r.value_scale = mapping.scale;
        r.value_offset = mapping.offset;
        r.value_unit = mapping.unit.c_str();
        return r;
    }
};

std::string describe(const topology::BranchMeasures &m)
{
    std::ostringstream s;
    s << "persistence " << m.absolute[topology::kPersistence] << ", volume " << m.absolute[topology::kVolume]
      << " voxels, hypervolume " << m.absolute[topology::kHypervolume];
    return s.str();
}

} // namespace

topology::ImportanceFn simplifier_importance(PluginInstance &simplifier, const ValueMapping &mapping)
{
    const auto &table = simplifier.interface<arbor_simplifier_v1>(ARBOR_INTERFACE_SIMPLIFIER);
    auto measures = std::make_shared<MeasureTable>(mapping);
    const arbor_measure_rows schema = measures->rows(0);
    simplifier.check(simplifier.call("simplifier.prepare", table.prepare, &schema), "preparing the simplifier");
    return [&simplifier, &table, measures](const std::vector<topology::BranchMeasures> &rows,
                                           std::vector<double> &out) {
        MeasureTable &m = *measures;
        m.fill(rows);
        // Rows the plugin leaves unset stay NaN and are refused below.
        out.assign(rows.size(), std::numeric_limits<double>::quiet_NaN());
        const arbor_measure_rows batch = m.rows(static_cast<uint32_t>(rows.size()));
        simplifier.check(simplifier.call("simplifier.importance", table.importance, &batch, out.data()),
                         "ranking branches");
        for (std::size_t r = 0; r < rows.size(); ++r)
            if (!std::isfinite(out[r]) || out[r] < 0.0)
                throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                                  simplifier.id() + " returned importance " + std::to_string(out[r]) +
                                      " for a branch (" + describe(rows[r]) +
                                      "); an importance must be a finite number >= 0");
    };
}

} // namespace arbor
