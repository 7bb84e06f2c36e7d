// arbor/sdk/simplifier.hpp - base class for simplifier plugins written in C++.
//
// Derive and implement prepare (look up the measure columns you need with
// MeasureColumns) and importance.  NULL pointers and record sizes are checked
// here; the host checks that every importance is finite and >= 0.
#pragma once

#include <arbor/simplifier.h>

#include "instance.hpp"

#include <cstring>
#include <string>

namespace arbor::sdk {

// Column lookup in a measure table (arbor_measure_rows).
class MeasureColumns {
public:
    explicit MeasureColumns(const arbor_measure_rows &schema) : schema_(schema) {}

    // Index of the column `id`; fails with ARBOR_ERROR_NOT_FOUND naming the
    // measure and the columns the host offers.
    uint32_t find(const char *id) const
    {
        for (uint32_t c = 0; c < schema_.measure_count; ++c)
            if (schema_.measure_ids[c] && std::strcmp(schema_.measure_ids[c], id) == 0)
                return c;
        std::string offered;
        for (uint32_t c = 0; c < schema_.measure_count; ++c)
            offered += (c ? ", " : "") + std::string(schema_.measure_ids[c] ? schema_.measure_ids[c] : "?");
        fail(ARBOR_ERROR_NOT_FOUND,
             std::string("the host provides no measure '") + id + "' (it offers: " + offered + ")");
    }

private:
    const arbor_measure_rows &schema_;
};

class Simplifier : public Instance {
public:
    Simplifier(const arbor_plugin_descriptor &descriptor, const arbor_host *host,
               std::vector<ParamSpec> params = {})
        : Instance(descriptor, host, std::move(params))
    {
        table_.prepare = &c_prepare;
        table_.importance = &c_importance;
    }

    // Before a pruning run: find the columns the importance needs.
    virtual void prepare(const arbor_measure_rows &schema) = 0;
    // out[r] for every row r of `rows` (same columns as the schema).
    virtual void importance(const arbor_measure_rows &rows, double *out) = 0;

protected:
    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_SIMPLIFIER)
            return &table_;
        return Instance::find_interface(id);
    }

private:
    static Simplifier &self_of(Instance &i) { return static_cast<Simplifier &>(i); }

    static void require_rows(const arbor_measure_rows *rows, bool need_values)
    {
        require_record(rows, "measure rows");
        if (rows->measure_count > 0 && !rows->measure_ids)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "measure rows have no measure ids");
        if (need_values && rows->row_count > 0 && (!rows->measures || !rows->relative_measures))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "measure rows have no values");
    }

    static arbor_status c_prepare(arbor_plugin *plugin, const arbor_measure_rows *schema)
    {
        return guarded(plugin, [&](Instance &self) {
            require_rows(schema, false);
            self_of(self).prepare(*schema);
        });
    }

    static arbor_status c_importance(arbor_plugin *plugin, const arbor_measure_rows *rows, double *out)
    {
        return guarded(plugin, [&](Instance &self) {
            require_rows(rows, true);
            if (!out)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "out is NULL");
            self_of(self).importance(*rows, out);
        });
    }

    arbor_simplifier_v1 table_{};
};

} // namespace arbor::sdk
