// arbor/sdk/depictor.hpp - base class for relationship depictors written in
// C++.  Derive and implement depict and related (and legend, when the
// depictor has one); records and branch indices are checked here.
#pragma once

#include <arbor/depictor.h>

#include "branch_tree.hpp"
#include "instance.hpp"
#include "task.hpp"

namespace arbor::sdk {

class Depictor : public Instance {
public:
    Depictor(const arbor_plugin_descriptor &descriptor, const arbor_host *host, std::vector<ParamSpec> params = {})
        : Instance(descriptor, host, std::move(params))
    {
        table_.depict = &c_depict;
        table_.related = &c_related;
        table_.legend = &c_legend;
    }

    // `selected` is -1 or a valid branch; `out` arrays hold tree.size()
    // entries pre-filled with neutral values.
    virtual void depict(const BranchTreeView &tree, int32_t selected, arbor_depiction &out, const Task &task) = 0;
    virtual bool related(const BranchTreeView &tree, uint32_t a, uint32_t b) = 0;
    // Draw into `image` (checked: non-NULL rgba, positive size); the default
    // has no legend.
    virtual void legend(const BranchTreeView &, int32_t, arbor_image &, const Task &)
    {
        fail(ARBOR_ERROR_UNSUPPORTED, std::string(descriptor().id) + " draws no legend");
    }

protected:
    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_DEPICTOR)
            return &table_;
        return Instance::find_interface(id);
    }

private:
    static Depictor &self_of(Instance &i) { return static_cast<Depictor &>(i); }

    static int32_t checked_selection(const arbor_depiction_request &r, const BranchTreeView &tree)
    {
        if (r.selected_branch < -1 || (r.selected_branch >= 0 && static_cast<uint32_t>(r.selected_branch) >= tree.size()))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "selected branch " + std::to_string(r.selected_branch) +
                                                   " out of range (" + std::to_string(tree.size()) + " branches)");
        return r.selected_branch;
    }

    static arbor_status c_depict(arbor_plugin *plugin, const arbor_depiction_request *request, arbor_depiction *out,
                                 arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "depiction request");
            require_record(out, "depiction");
            const BranchTreeView tree(request->tree);
            if (out->branch_count != tree.size() || !out->role || !out->opacity_at_saddle ||
                !out->opacity_at_extremum || !out->hue || !out->saturation)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "depiction arrays missing or not sized for the tree");
            self_of(self).depict(tree, checked_selection(*request, tree), *out, Task(task));
        });
    }

    static arbor_status c_related(arbor_plugin *plugin, const arbor_branch_tree *tree_record, uint32_t a, uint32_t b,
                                  arbor_bool32 *related_out)
    {
        return guarded(plugin, [&](Instance &self) {
            const BranchTreeView tree(tree_record);
            if (a >= tree.size() || b >= tree.size())
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "branch index out of range");
            if (!related_out)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "related is NULL");
            *related_out = self_of(self).related(tree, a, b) ? 1 : 0;
        });
    }

    static arbor_status c_legend(arbor_plugin *plugin, const arbor_depiction_request *request, arbor_image *image,
                                 arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "depiction request");
            require_record(image, "legend image");
            if (!image->rgba || image->width == 0 || image->height == 0 ||
                image->row_stride < 4 * static_cast<int64_t>(image->width))
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "legend image has no pixels or a bad row stride");
            const BranchTreeView tree(request->tree);
            self_of(self).legend(tree, checked_selection(*request, tree), *image, Task(task));
        });
    }

    arbor_depictor_v1 table_{};
};

} // namespace arbor::sdk
