// n_measure_simplifier.cpp - the n-measure importance (thesis §4.5.3): any
// n >= 2 of the host's measures, relative to the root, as a point in an
// n-dimensional attribute space; importance is the area of the hypotenuse
// face of the simplex its axis projections span.  With persistence, volume
// and hypervolume it equals ITri.
#include "importance_area.hpp"
#include "simplifier_classes.hpp"

#include <algorithm>
#include <array>

namespace arbor::simplifiers {

const arbor_plugin_descriptor kNMeasureDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_NONE,
    "org.arbor.simplifier.n-measure",
    ARBOR_KIND_SIMPLIFIER,
    "n-measure importance",
    "1.0.0",
    "Arbor",
    "Ranks branches by the hypotenuse-face area spanned by any two or more of their relative measures "
    "(persistence, volume, hypervolume, relative-hypervolume...), the generalisation of ITri.",
    "",
};

namespace {

constexpr std::size_t kMaxMeasures = 16;

// Measure ids separated by ',' or '+' ("persistence+volume" reads as a sum
// of axes and fits in a comma-separated list of simplifier settings).
std::vector<std::string> split_list(const std::string &text)
{
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find_first_of(",+", start);
        if (end == std::string::npos)
            end = text.size();
        std::string item = text.substr(start, end - start);
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (!item.empty())
            out.push_back(item);
        start = end + 1;
    }
    return out;
}

class NMeasureSimplifier final : public sdk::Simplifier {
public:
    explicit NMeasureSimplifier(const arbor_host *host)
        : Simplifier(kNMeasureDescriptor, host,
                     {sdk::ParamSpec::text("measures", "Measures", "persistence,volume,hypervolume")
                          .hint("Measure ids separated by commas or '+', at least two, e.g. persistence,volume or "
                                "persistence+volume+hypervolume+relative-hypervolume")})
    {
    }

    void prepare(const arbor_measure_rows &schema) override
    {
        const std::vector<std::string> ids = split_list(params().text("measures"));
        if (ids.size() < 2)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT,
                      "measures: the n-measure importance needs at least two measures (got '" +
                          params().text("measures") + "'); for one, use a single-measure simplifier");
        if (ids.size() > kMaxMeasures)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "measures: at most 16 measures");
        const sdk::MeasureColumns columns(schema);
        columns_.clear();
        for (const std::string &id : ids) {
            const uint32_t c = columns.find(id.c_str());
            if (std::find(columns_.begin(), columns_.end(), c) != columns_.end())
                sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "measures: '" + id + "' is listed twice");
            columns_.push_back(c);
        }
        width_ = schema.measure_count;
    }

    void importance(const arbor_measure_rows &rows, double *out) override
    {
        if (columns_.empty() || rows.measure_count != width_)
            sdk::fail(ARBOR_ERROR_INVALID_ARGUMENT, "rows do not have the columns given to prepare");
        std::array<double, kMaxMeasures> m{};
        for (uint32_t r = 0; r < rows.row_count; ++r) {
            const double *row = rows.relative_measures + std::size_t{r} * width_;
            for (std::size_t i = 0; i < columns_.size(); ++i)
                m[i] = row[columns_[i]];
            out[r] = hypotenuse_face_area(m.data(), columns_.size());
        }
    }

private:
    std::vector<uint32_t> columns_;
    uint32_t width_ = 0;
};

} // namespace

sdk::Instance *create_n_measure(const arbor_host *host)
{
    return new NMeasureSimplifier(host);
}

} // namespace arbor::simplifiers
