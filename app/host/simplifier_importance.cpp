#include "simplifier_importance.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

namespace arbor {

namespace {

struct MeasureTable {
    const char *ids[topology::kMeasureCount];
    std::vector<double> absolute, relative;

    MeasureTable()
    {
        for (int m = 0; m < topology::kMeasureCount; ++m)
            ids[m] = topology::measure_id(m);
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

topology::ImportanceFn simplifier_importance(PluginInstance &simplifier)
{
    const auto &table = simplifier.interface<arbor_simplifier_v1>(ARBOR_INTERFACE_SIMPLIFIER);
    auto measures = std::make_shared<MeasureTable>();
    const arbor_measure_rows schema = measures->rows(0);
    simplifier.check(table.prepare(simplifier.get(), &schema), "preparing the simplifier");
    return [&simplifier, &table, measures](const std::vector<topology::BranchMeasures> &rows,
                                           std::vector<double> &out) {
        MeasureTable &m = *measures;
        const std::size_t width = topology::kMeasureCount;
        m.absolute.resize(rows.size() * width);
        m.relative.resize(rows.size() * width);
        for (std::size_t r = 0; r < rows.size(); ++r)
            for (std::size_t c = 0; c < width; ++c) {
                m.absolute[r * width + c] = rows[r].absolute[c];
                m.relative[r * width + c] = rows[r].relative[c];
            }
        // Rows the plugin leaves unset stay NaN and are refused below.
        out.assign(rows.size(), std::numeric_limits<double>::quiet_NaN());
        const arbor_measure_rows batch = m.rows(static_cast<uint32_t>(rows.size()));
        simplifier.check(table.importance(simplifier.get(), &batch, out.data()), "ranking branches");
        for (std::size_t r = 0; r < rows.size(); ++r)
            if (!std::isfinite(out[r]) || out[r] < 0.0)
                throw PluginError(ARBOR_ERROR_OUT_OF_RANGE,
                                  simplifier.id() + " returned importance " + std::to_string(out[r]) +
                                      " for a branch (" + describe(rows[r]) +
                                      "); an importance must be a finite number >= 0");
    };
}

} // namespace arbor
