// arbor/sdk/renderer.hpp - base class for renderer plugins written in C++.
// Derive and implement render; the request's records (volume, labels,
// transfer functions, camera) and the output image are checked here.
#pragma once

#include <arbor/renderer.h>

#include "instance.hpp"
#include "task.hpp"

#include <cmath>

namespace arbor::sdk {

class Renderer : public Instance {
public:
    Renderer(const arbor_plugin_descriptor &descriptor, const arbor_host *host, std::vector<ParamSpec> params = {})
        : Instance(descriptor, host, std::move(params))
    {
        table_.render = &c_render;
    }

    virtual void render(const arbor_render_request &request, arbor_image &out, const Task &task) = 0;

protected:
    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_RENDERER)
            return &table_;
        return Instance::find_interface(id);
    }

private:
    static void check_request(const arbor_render_request &r)
    {
        require_record(r.volume, "volume");
        require_record(r.transfer_functions, "transfer functions");
        require_record(r.camera, "camera");
        const arbor_volume &v = *r.volume;
        if (!v.voxels || arbor_voxel_size(v.voxel_type) == 0)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "volume has no voxels or an unknown voxel type");
        for (int a = 0; a < 3; ++a)
            if (v.dims[a] <= 0 || !(v.spacing[a] > 0))
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "volume dims and spacing must be positive");
        const arbor_tf_set &tf = *r.transfer_functions;
        if (tf.branch_count == 0 || tf.lut_size < 2 || !tf.domain || !tf.lut || !(tf.opacity_unit_distance > 0))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "transfer functions are empty or malformed");
        if (r.labels) {
            require_record(r.labels, "label map");
            for (int a = 0; a < 3; ++a)
                if (r.labels->dims[a] != v.dims[a])
                    fail(ARBOR_ERROR_INVALID_ARGUMENT, "label map dims differ from the volume's");
            if (!r.labels->labels || r.labels->label_count > tf.branch_count)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "label map has no labels or more labels than transfer functions");
        }
        const arbor_camera &c = *r.camera;
        const double d[3] = {c.focal_point[0] - c.position[0], c.focal_point[1] - c.position[1],
                             c.focal_point[2] - c.position[2]};
        if (!(std::hypot(d[0], d[1], d[2]) > 0) || !(std::hypot(c.view_up[0], c.view_up[1], c.view_up[2]) > 0))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "camera position equals its focal point, or view-up is zero");
        if (c.projection == ARBOR_PROJECTION_PERSPECTIVE ? !(c.view_angle > 0 && c.view_angle < 180)
                                                          : !(c.parallel_scale > 0))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "camera view angle or parallel scale out of range");
    }

    static arbor_status c_render(arbor_plugin *plugin, const arbor_render_request *request, arbor_image *out,
                                 arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "render request");
            require_record(out, "image");
            if (!out->rgba || out->width == 0 || out->height == 0 ||
                out->row_stride < 4 * static_cast<int64_t>(out->width))
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "image has no pixels or a bad row stride");
            check_request(*request);
            static_cast<Renderer &>(self).render(*request, *out, Task(task));
        });
    }

    arbor_renderer_v1 table_{};
};

} // namespace arbor::sdk
