// arbor/sdk/renderer.hpp - base class for renderer plugins written in C++.
// Derive and implement render (arbor.renderer/1: full frames), or pass
// Interface::v2 and implement render_region (arbor.renderer/2: tiles,
// passes, revisions; then /1 is offered too, as one full-frame FULL pass).
// An OpenGL renderer may also call offer_gl() and implement render_gl and
// release_gl (arbor.renderer-gl/1: into a texture of the host's context).
// The request's records (volume, labels, transfer functions, camera, the
// region) and the output image are checked here.
#pragma once

#include <arbor/renderer.h>

#include "instance.hpp"
#include "task.hpp"

#include <cmath>

namespace arbor::sdk {

class Renderer : public Instance {
public:
    enum class Interface { v1, v2 };

    Renderer(const arbor_plugin_descriptor &descriptor, const arbor_host *host, std::vector<ParamSpec> params = {},
             Interface offered = Interface::v1)
        : Instance(descriptor, host, std::move(params)), offered_(offered)
    {
        table_.render = &c_render;
        table2_.struct_size = sizeof table2_;
        table2_.render = &c_render2;
        device_table_.struct_size = sizeof device_table_;
        device_table_.describe = &c_describe;
        gl_table_.struct_size = sizeof gl_table_;
        gl_table_.render_gl = &c_render_gl;
        gl_table_.release_gl = &c_release_gl;
    }

    // arbor.renderer/1: the whole frame, full quality.  A v2 renderer need
    // not override it: it becomes render_region of the full frame.
    virtual void render(const arbor_render_request &request, arbor_image &out, const Task &task)
    {
        arbor_render_request_v2 r{};
        r.struct_size = sizeof r;
        r.pass = ARBOR_RENDER_PASS_FULL;
        r.volume = request.volume;
        r.labels = request.labels;
        r.transfer_functions = request.transfer_functions;
        r.camera = request.camera;
        for (int c = 0; c < 4; ++c)
            r.background[c] = request.background[c];
        r.volume_revision = request.volume_revision;
        r.labels_revision = request.labels_revision;
        r.transfer_functions_revision = 0; // unknown: /1 has none
        r.frame_width = r.region_width = out.width;
        r.frame_height = r.region_height = out.height;
        render_region(r, out, task);
    }

    // arbor.renderer/2: request.pass of the region into out (region-sized).
    virtual void render_region(const arbor_render_request_v2 &, arbor_image &, const Task &)
    {
        fail(ARBOR_ERROR_UNSUPPORTED, "this renderer offers arbor.renderer/1 only");
    }

    // arbor.renderer-gl/1: request.pass of the region into the target
    // texture, with the host's context current on the calling thread.
    virtual void render_gl(const arbor_render_request_v2 &, const arbor_gl_target &, const Task &)
    {
        fail(ARBOR_ERROR_UNSUPPORTED, "this renderer does not render into the host's OpenGL context");
    }
    // Deletes what render_gl made in the host's context (current now).
    virtual void release_gl() {}

protected:
    // Offer arbor.renderer-gl/1 (call in the constructor of a v2 renderer).
    void offer_gl() { gl_offered_ = true; }

    // arbor.render-device/1: say what this instance renders on.  Either
    // call set_device in the constructor, or call offer_device there and
    // override find_device to find it out when the host first asks (it
    // calls set_device; an exception becomes the call's error).
    void set_device(arbor_device_kind kind, std::string name)
    {
        device_kind_ = kind;
        device_name_ = std::move(name);
        device_offered_ = true;
    }
    void offer_device() { device_offered_ = true; }
    virtual void find_device() { fail(ARBOR_ERROR_INTERNAL, "the renderer did not say what it renders on"); }

    const void *find_interface(std::string_view id) const override
    {
        if (id == ARBOR_INTERFACE_RENDER_DEVICE && device_offered_)
            return &device_table_;
        if (id == ARBOR_INTERFACE_RENDERER)
            return &table_;
        if (id == ARBOR_INTERFACE_RENDERER_2 && offered_ == Interface::v2)
            return &table2_;
        if (id == ARBOR_INTERFACE_RENDERER_GL && offered_ == Interface::v2 && gl_offered_)
            return &gl_table_;
        return Instance::find_interface(id);
    }

private:
    template <typename Request> static void check_request(const Request &r)
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
            check_hierarchy(*r.labels);
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

    // How the labels nest (since ABI 1.6), when the map says: a tree rooted
    // at label 0 whose parents come first, with finite saddle values.
    static void check_hierarchy(const arbor_label_map &m)
    {
        if (!ARBOR_HAS_FIELD(arbor_label_map, m.struct_size, saddle_value) || !m.parent || !m.saddle_value)
            return;
        for (uint32_t l = 0; l < m.label_count; ++l)
            if ((l == 0 ? m.parent[l] != -1 : m.parent[l] < 0 || static_cast<uint32_t>(m.parent[l]) >= l) ||
                !std::isfinite(m.saddle_value[l]))
                fail(ARBOR_ERROR_INVALID_ARGUMENT,
                     "label map's hierarchy: label " + std::to_string(l) +
                         (std::isfinite(m.saddle_value[l]) ? " has a parent that does not come before it"
                                                           : " has a saddle value that is not finite"));
    }

    static arbor_status c_render(arbor_plugin *plugin, const arbor_render_request *request, arbor_image *out,
                                 arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "render request");
            check_image(out);
            check_request(*request);
            static_cast<Renderer &>(self).render(*request, *out, Task(task));
        });
    }

    static void check_image(const arbor_image *out)
    {
        require_record(out, "image");
        if (!out->rgba || out->width == 0 || out->height == 0 ||
            out->row_stride < 4 * static_cast<int64_t>(out->width))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "image has no pixels or a bad row stride");
        if (ARBOR_HAS_FIELD(arbor_image, out->struct_size, depth_stride) && out->depth_stride != 0 &&
            out->depth_stride < static_cast<int64_t>(out->width))
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "image has a depth stride below its width");
    }

    static arbor_status c_render2(arbor_plugin *plugin, const arbor_render_request_v2 *request, arbor_image *out,
                                  arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "render request");
            check_image(out);
            check_request(*request);
            check_passes(*request);
            if (request->region_width != out->width || request->region_height != out->height)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "the region differs from the image's size");
            static_cast<Renderer &>(self).render_region(*request, *out, Task(task));
        });
    }

    // The pass and the region of an arbor.renderer/2 request.
    static void check_passes(const arbor_render_request_v2 &r)
    {
        if (r.pass > ARBOR_RENDER_PASS_SUPERSAMPLE)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "unknown render pass " + std::to_string(r.pass));
        if (r.pass == ARBOR_RENDER_PASS_SUPERSAMPLE && r.sample_index == 0)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "a supersample pass counts its samples from 1");
        if (r.frame_width == 0 || r.frame_height == 0 || r.region_width == 0 || r.region_height == 0 ||
            r.region_x >= r.frame_width || r.region_y >= r.frame_height ||
            r.region_width > r.frame_width - r.region_x || r.region_height > r.frame_height - r.region_y)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, "the region is empty or lies outside the frame");
    }

    static arbor_status c_render_gl(arbor_plugin *plugin, const arbor_render_request_v2 *request,
                                    const arbor_gl_target *target, arbor_task *task)
    {
        return guarded(plugin, [&](Instance &self) {
            require_record(request, "render request");
            require_record(target, "OpenGL target");
            check_request(*request);
            check_passes(*request);
            if (target->texture == 0 || target->width != request->frame_width ||
                target->height != request->frame_height)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, "the OpenGL target names no texture or is not the frame's size");
            static_cast<Renderer &>(self).render_gl(*request, *target, Task(task));
        });
    }

    static arbor_status c_release_gl(arbor_plugin *plugin)
    {
        return guarded(plugin, [&](Instance &self) { static_cast<Renderer &>(self).release_gl(); });
    }

    static arbor_status c_describe(const arbor_plugin *plugin, arbor_render_device *out)
    {
        if (!plugin || !out || out->struct_size < ARBOR_MIN_SIZE(arbor_render_device))
            return ARBOR_ERROR_INVALID_ARGUMENT;
        return guarded(plugin, [&](Instance &instance) {
            auto &self = static_cast<Renderer &>(instance);
            if (self.device_kind_ == 0)
                self.find_device();
            out->kind = self.device_kind_;
            out->name = self.device_name_.c_str();
        });
    }

    Interface offered_;
    arbor_device_kind device_kind_ = 0;
    std::string device_name_;
    bool device_offered_ = false, gl_offered_ = false;
    arbor_render_device_v1 device_table_{};
    arbor_renderer_v1 table_{};
    arbor_renderer_v2 table2_{};
    arbor_renderer_gl_v1 gl_table_{};
};

} // namespace arbor::sdk
