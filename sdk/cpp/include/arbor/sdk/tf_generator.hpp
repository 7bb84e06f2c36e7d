// arbor/sdk/tf_generator.hpp - base class for transfer-function generators
// written in C++.  Derive and implement generate; the request, the tree and
// the output arrays are checked here.
#pragma once

#include <arbor/transfer_function.h>

#include "branch_tree.hpp"
#include "instance.hpp"
#include "task.hpp"

namespace arbor::sdk {

class TfGenerator : public Instance {
public:
    TfGenerator(const arbor_plugin_descriptor &descriptor, const arbor_host *host, std::vector<ParamSpec> params = {})
        : Instance(descriptor, host, std::move(params))
    {
        table_.generate = &c_generate;
    }

    // `out` has domain, lut and point_offsets for tree.size() branches; set
    // out.points to memory from task.allocate.
    virtual void generate(const arbor_tf_request &request, const BranchTreeView &tree, arbor_tf_set &out,
                          const Task &task) = 0;

protected:
    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_TF_GENERATOR)
            return &table_;
        return Instance::find_interface(id);
    }

private:
    static arbor_status c_generate(arbor_plugin *plugin, const arbor_tf_request *request, arbor_tf_set *out,
                                   arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "transfer-function request");
            require_record(out, "transfer-function set");
            const BranchTreeView tree(request->tree);
            if (out->branch_count != tree.size() || out->lut_size < 2 || !out->domain || !out->lut ||
                !out->point_offsets)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "transfer-function arrays missing or not sized for the tree");
            if (request->depiction && (request->depiction->branch_count != tree.size()))
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "the depiction is not sized for the tree");
            if (!std::isfinite(request->value_range[0]) || !std::isfinite(request->value_range[1]) ||
                request->value_range[1] < request->value_range[0])
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "value range is not a finite interval");
            static_cast<TfGenerator &>(self).generate(*request, tree, *out, Task(task));
        });
    }

    arbor_tf_generator_v1 table_{};
};

} // namespace arbor::sdk
