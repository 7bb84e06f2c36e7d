// arbor/sdk/filter.hpp - base class for filter plugins written in C++.
//
// Derive and implement output_type and apply; argument checks common to every
// filter (NULL pointers, record sizes, matching dims) are done here.
#pragma once

#include <arbor/filter.h>

#include "instance.hpp"
#include "task.hpp"

namespace arbor::sdk {

class Filter : public Instance {
public:
    Filter(const arbor_plugin_descriptor &descriptor, const arbor_host *host,
           std::vector<ParamSpec> params = {})
        : Instance(descriptor, host, std::move(params))
    {
        table_.output_type = &c_output_type;
        table_.apply = &c_apply;
    }

    virtual arbor_voxel_type output_type(const arbor_volume &input) = 0;
    virtual void apply(const arbor_volume &input, arbor_volume &output, const Task &task) = 0;

protected:
    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_FILTER)
            return &table_;
        return Instance::find_interface(id);
    }

private:
    static Filter &self_of(Instance &i) { return static_cast<Filter &>(i); }

    static void require_volume(const arbor_volume *v, const char *what)
    {
        require_record(v, what);
        if (!v->voxels)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, std::string(what) + " has no voxels");
        if (arbor_voxel_size(v->voxel_type) == 0)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, std::string(what) + " has an unknown voxel type");
        for (int a = 0; a < 3; ++a)
            if (v->dims[a] <= 0)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, std::string(what) + " dims must be positive");
    }

    static arbor_status c_output_type(arbor_plugin *plugin, const arbor_volume *input,
                                      arbor_voxel_type *out_type)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(input, "input volume");
            if (!out_type)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "out_type is NULL");
            *out_type = self_of(self).output_type(*input);
        });
    }

    static arbor_status c_apply(arbor_plugin *plugin, const arbor_volume *input,
                                arbor_volume *output, arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_volume(input, "input volume");
            require_volume(output, "output volume");
            for (int a = 0; a < 3; ++a)
                if (input->dims[a] != output->dims[a])
                    fail(ARBOR_ERROR_INVALID_ARGUMENT, "input and output dims differ");
            if (input->voxels == output->voxels)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "input and output alias");
            self_of(self).apply(*input, *output, Task(task));
        });
    }

    arbor_filter_v1 table_{};
};

} // namespace arbor::sdk
