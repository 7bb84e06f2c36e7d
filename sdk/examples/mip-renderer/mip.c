/*
 * mip.c - an Arbor renderer in plain C: maximum-intensity projection on the
 * CPU.  Every pixel shows the largest value along its ray, as a grey level
 * from the volume's minimum (black) to its maximum (white), or, with
 * `colour`, in the colour the transfer function of the structure that
 * brightest sample belongs to gives it.  A MIP shows vessels and bone
 * through everything around them, whatever the opacities.
 *
 * Rays follow the camera (perspective or orthographic, LPS millimetres)
 * through the volume's grid, taken into voxel indices through its origin,
 * direction cosines and spacing; samples are `step` of the smallest spacing
 * apart and read the nearest voxel.  depth is the distance to the brightest
 * sample.
 *
 * Rules it follows (sdk/docs/contract.md): the request's pointers are
 * borrowed for the call, so what it keeps between calls (the volume's value
 * range) is a copy, keyed by the volume pointer and volume_revision, with
 * revision 0 meaning "unknown: look again"; it writes every pixel of the
 * host's image (premultiplied, over the request's background); it reports
 * progress per block of rows and stops when cancelled.  It offers
 * arbor.renderer/1 only, so the host renders whole frames with it and uses
 * them for coarse passes too; it measures no visibility and leaves the
 * host's NaNs in label_visibility.
 */
#include <arbor/arbor.h>
#include <arbor/param_check.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const arbor_plugin_descriptor descriptor = {
    .struct_size = sizeof(arbor_plugin_descriptor),
    .id = "org.arbor.example.mip",
    .kind = ARBOR_KIND_RENDERER,
    .name = "Maximum-intensity projection (example)",
    .version = "1.0.0",
    .vendor = "Arbor",
    .description = "The largest value along each ray, grey from the volume's minimum to its maximum or in its "
                   "structure's colour. Example of a renderer in plain C.",
    .url = "",
};

enum { STEP, COLOUR, PARAM_COUNT };

static const arbor_param_desc params[PARAM_COUNT] = {
    [STEP] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "step", .name = "Step",
              .group = "Quality", .unit = "voxels",
              .hint = "Distance between samples along a ray, in smallest voxel spacings", .components = 1,
              .min_value = 0.05, .max_value = 4, .default_value = {0.5}, .default_text = ""},
    [COLOUR] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_BOOL, .id = "colour",
                .name = "Colour by structure", .group = "", .unit = "",
                .hint = "Colour each pixel as the transfer function of the brightest sample's structure does, "
                        "instead of grey",
                .components = 1, .min_value = 0, .max_value = 1, .default_value = {0}, .default_text = ""},
};

typedef struct renderer {
    arbor_plugin plugin;
    arbor_param_slot values[PARAM_COUNT];
    /* The value range of the volume last seen, and what it was seen as. */
    const void *range_voxels;
    uint64_t range_revision;
    double range_min, range_max;
    char error[256];
} renderer;

static renderer *self_of(const arbor_plugin *p) { return p ? (renderer *)p->plugin_data : NULL; }

static arbor_status fail(renderer *r, arbor_status status, const char *message)
{
    snprintf(r->error, sizeof r->error, "%s", message);
    return status;
}

static double voxel(const arbor_volume *v, int64_t i, int64_t j, int64_t k)
{
    const unsigned char *p =
        (const unsigned char *)v->voxels + i * v->strides[0] + j * v->strides[1] + k * v->strides[2];
    switch (v->voxel_type) {
    case ARBOR_VOXEL_U8: return *(const uint8_t *)p;
    case ARBOR_VOXEL_I8: return *(const int8_t *)p;
    case ARBOR_VOXEL_U16: { uint16_t x; memcpy(&x, p, 2); return x; }
    case ARBOR_VOXEL_I16: { int16_t x; memcpy(&x, p, 2); return x; }
    case ARBOR_VOXEL_U32: { uint32_t x; memcpy(&x, p, 4); return x; }
    case ARBOR_VOXEL_I32: { int32_t x; memcpy(&x, p, 4); return x; }
    case ARBOR_VOXEL_F32: { float x; memcpy(&x, p, 4); return x; }
    default: { double x; memcpy(&x, p, 8); return x; }
    }
}

/* The volume's stored minimum and maximum, found again only when the volume
 * (or its revision) changed. */
static void value_range(renderer *r, const arbor_volume *v, uint64_t revision)
{
    int64_t i, j, k;
    if (revision != 0 && revision == r->range_revision && v->voxels == r->range_voxels)
        return;
    r->range_min = INFINITY;
    r->range_max = -INFINITY;
    for (k = 0; k < v->dims[2]; ++k)
        for (j = 0; j < v->dims[1]; ++j)
            for (i = 0; i < v->dims[0]; ++i) {
                const double x = voxel(v, i, j, k);
                if (x < r->range_min)
                    r->range_min = x;
                if (x > r->range_max)
                    r->range_max = x;
            }
    r->range_voxels = v->voxels;
    r->range_revision = revision;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int normalise(double a[3])
{
    const double n = sqrt(dot(a, a));
    if (!(n > 0))
        return 0;
    a[0] /= n;
    a[1] /= n;
    a[2] /= n;
    return 1;
}

/* The inverse of M = D * diag(spacing), which takes voxel indices to mm. */
static int index_matrix(const arbor_volume *v, double inv[9])
{
    double m[9], det;
    int r, c;
    for (r = 0; r < 3; ++r)
        for (c = 0; c < 3; ++c)
            m[3 * r + c] = v->direction[3 * r + c] * v->spacing[c];
    det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
    if (!(fabs(det) > 0))
        return 0;
    inv[0] = (m[4] * m[8] - m[5] * m[7]) / det;
    inv[1] = (m[2] * m[7] - m[1] * m[8]) / det;
    inv[2] = (m[1] * m[5] - m[2] * m[4]) / det;
    inv[3] = (m[5] * m[6] - m[3] * m[8]) / det;
    inv[4] = (m[0] * m[8] - m[2] * m[6]) / det;
    inv[5] = (m[2] * m[3] - m[0] * m[5]) / det;
    inv[6] = (m[3] * m[7] - m[4] * m[6]) / det;
    inv[7] = (m[1] * m[6] - m[0] * m[7]) / det;
    inv[8] = (m[0] * m[4] - m[1] * m[3]) / det;
    return 1;
}

static void apply(const double m[9], const double x[3], double out[3])
{
    out[0] = m[0] * x[0] + m[1] * x[1] + m[2] * x[2];
    out[1] = m[3] * x[0] + m[4] * x[1] + m[5] * x[2];
    out[2] = m[6] * x[0] + m[7] * x[1] + m[8] * x[2];
}

/* Where a ray o + t d (t in mm, index-space o and d) enters and leaves the
 * grid's box [-0.5, n - 0.5]; 0 when it misses. */
static int clip(const arbor_volume *v, const double o[3], const double d[3], double *t0, double *t1)
{
    int a;
    *t0 = 0.0;
    *t1 = INFINITY;
    for (a = 0; a < 3; ++a) {
        const double lo = -0.5, hi = (double)v->dims[a] - 0.5;
        if (fabs(d[a]) < 1e-300) {
            if (o[a] < lo || o[a] > hi)
                return 0;
        } else {
            double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
            if (ta > tb) {
                const double x = ta;
                ta = tb;
                tb = x;
            }
            if (ta > *t0)
                *t0 = ta;
            if (tb < *t1)
                *t1 = tb;
        }
    }
    return *t0 < *t1;
}

static arbor_status check_request(renderer *r, const arbor_render_request *q, const arbor_image *out)
{
    const arbor_volume *v;
    int a;
    if (!q || q->struct_size < ARBOR_MIN_SIZE(arbor_render_request) || !q->volume || !q->camera ||
        !q->transfer_functions)
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: NULL or malformed request");
    if (!out || out->struct_size < ARBOR_MIN_SIZE(arbor_image) || !out->rgba || out->width == 0 ||
        out->height == 0 || out->row_stride < 4 * (int64_t)out->width)
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: NULL or malformed image");
    v = q->volume;
    if (v->struct_size < ARBOR_MIN_SIZE(arbor_volume) || !v->voxels || arbor_voxel_size(v->voxel_type) == 0)
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: the volume is malformed or has no voxels");
    for (a = 0; a < 3; ++a)
        if (v->dims[a] < 1 || !(v->spacing[a] > 0))
            return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: the volume has a size or spacing below 1");
    if (q->camera->struct_size < ARBOR_MIN_SIZE(arbor_camera))
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: the camera record is too small");
    if (q->transfer_functions->struct_size < ARBOR_MIN_SIZE(arbor_tf_set) || q->transfer_functions->branch_count < 1 ||
        !q->transfer_functions->lut || !q->transfer_functions->domain || q->transfer_functions->lut_size < 2)
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: malformed transfer functions");
    if (q->labels) {
        const arbor_label_map *l = q->labels;
        if (l->struct_size < ARBOR_MIN_SIZE(arbor_label_map) || !l->labels || l->dims[0] != v->dims[0] ||
            l->dims[1] != v->dims[1] || l->dims[2] != v->dims[2] ||
            l->label_count > q->transfer_functions->branch_count)
            return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: the label map does not fit the volume or the "
                                                         "transfer functions");
    }
    return ARBOR_OK;
}

static arbor_status render(arbor_plugin *plugin, const arbor_render_request *q, arbor_image *out, arbor_task *task)
{
    renderer *r = self_of(plugin);
    const arbor_volume *v;
    const arbor_camera *cam;
    const arbor_tf_set *tf;
    double to_index[9], forward[3], up[3], right[3], tan_half, aspect, step, span;
    float bg[4];
    uint32_t x, y;
    int colour, a;
    arbor_status status;
    if (!r)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    r->error[0] = '\0';
    if ((status = check_request(r, q, out)) != ARBOR_OK)
        return status;
    v = q->volume;
    cam = q->camera;
    tf = q->transfer_functions;
    if (!index_matrix(v, to_index))
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: the volume's direction matrix is singular");
    for (a = 0; a < 3; ++a) {
        forward[a] = cam->focal_point[a] - cam->position[a];
        up[a] = cam->view_up[a];
    }
    if (!normalise(forward))
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: the camera sits on its focal point");
    {
        const double along = dot(up, forward);
        for (a = 0; a < 3; ++a)
            up[a] -= along * forward[a];
    }
    if (!normalise(up))
        return fail(r, ARBOR_ERROR_INVALID_ARGUMENT, "render: view_up is parallel to the view direction");
    cross(forward, up, right);
    value_range(r, v, q->volume_revision);
    span = r->range_max > r->range_min ? r->range_max - r->range_min : 1.0;
    colour = r->values[COLOUR].value.number[0] != 0.0;
    step = r->values[STEP].value.number[0] * fmin(v->spacing[0], fmin(v->spacing[1], v->spacing[2]));
    tan_half = tan(cam->view_angle * 3.14159265358979323846 / 360.0);
    aspect = (double)out->width / (double)out->height;
    for (a = 0; a < 4; ++a)
        bg[a] = q->background[a];

    for (y = 0; y < out->height; ++y) {
        if (y % 16 == 0 && task && task->progress(task, (double)y / out->height, "maximum intensity"))
            return fail(r, ARBOR_ERROR_CANCELLED, "cancelled");
        for (x = 0; x < out->width; ++x) {
            /* The pixel's ray in mm, then in voxel indices. */
            const double sx = (2.0 * (x + 0.5) / out->width - 1.0) * aspect;
            const double sy = 1.0 - 2.0 * (y + 0.5) / out->height;
            double o[3], d[3], oi[3], di[3], t0, t1, t, best = -INFINITY, best_t = INFINITY;
            int64_t best_voxel[3] = {0, 0, 0};
            float *px = out->rgba + (int64_t)y * out->row_stride + 4 * (int64_t)x;
            float rgb[3], alpha = 0.0f;
            for (a = 0; a < 3; ++a) {
                if (cam->projection == ARBOR_PROJECTION_ORTHOGRAPHIC) {
                    o[a] = cam->position[a] + cam->parallel_scale * (sx * right[a] + sy * up[a]);
                    d[a] = forward[a];
                } else {
                    o[a] = cam->position[a];
                    d[a] = forward[a] + tan_half * (sx * right[a] + sy * up[a]);
                }
            }
            normalise(d);
            for (a = 0; a < 3; ++a)
                o[a] -= v->origin[a];
            apply(to_index, o, oi);
            apply(to_index, d, di);
            if (clip(v, oi, di, &t0, &t1)) {
                for (t = t0 + 0.5 * step; t < t1; t += step) {
                    int64_t ijk[3];
                    double value;
                    for (a = 0; a < 3; ++a) {
                        ijk[a] = (int64_t)floor(oi[a] + t * di[a] + 0.5);
                        ijk[a] = ijk[a] < 0 ? 0 : (ijk[a] >= v->dims[a] ? v->dims[a] - 1 : ijk[a]);
                    }
                    value = voxel(v, ijk[0], ijk[1], ijk[2]);
                    if (value > best) {
                        best = value;
                        best_t = t;
                        memcpy(best_voxel, ijk, sizeof ijk);
                    }
                }
            }
            if (best > -INFINITY) {
                alpha = 1.0f;
                if (colour) {
                    /* The brightest sample's structure and its function's colour there. */
                    const int64_t index = best_voxel[0] + v->dims[0] * (best_voxel[1] + v->dims[1] * best_voxel[2]);
                    const uint32_t label = q->labels ? q->labels->labels[index] : 0u;
                    const double lo = tf->domain[2 * label], hi = tf->domain[2 * label + 1];
                    double u = hi > lo ? (best - lo) / (hi - lo) : 1.0;
                    uint32_t e;
                    u = u < 0 ? 0 : (u > 1 ? 1 : u);
                    e = (uint32_t)floor(u * (tf->lut_size - 1) + 0.5);
                    for (a = 0; a < 3; ++a)
                        rgb[a] = tf->lut[((size_t)label * tf->lut_size + e) * 4 + a];
                } else {
                    const float g = (float)((best - r->range_min) / span);
                    rgb[0] = rgb[1] = rgb[2] = g;
                }
            } else {
                rgb[0] = rgb[1] = rgb[2] = 0.0f;
            }
            /* Premultiplied, over the background (straight colour + alpha). */
            for (a = 0; a < 3; ++a)
                px[a] = rgb[a] * alpha + (1.0f - alpha) * bg[a] * bg[3];
            px[3] = alpha + (1.0f - alpha) * bg[3];
            if (out->depth) {
                const int64_t depth_stride = ARBOR_HAS_FIELD(arbor_image, out->struct_size, depth_stride) &&
                                                     out->depth_stride > 0
                                                 ? out->depth_stride
                                                 : (int64_t)out->width;
                out->depth[(int64_t)y * depth_stride + x] = alpha > 0 ? (float)best_t : INFINITY;
            }
        }
    }
    if (task)
        task->progress(task, 1.0, "maximum intensity");
    return ARBOR_OK;
}

static const arbor_renderer_v1 renderer_interface = {.render = render};

static uint32_t param_count(const arbor_plugin *plugin)
{
    (void)plugin;
    return PARAM_COUNT;
}

static const arbor_param_desc *param_describe(const arbor_plugin *plugin, uint32_t index)
{
    (void)plugin;
    return index < PARAM_COUNT ? &params[index] : NULL;
}

static arbor_status param_get(const arbor_plugin *plugin, const char *id, arbor_param_value *out)
{
    renderer *r = self_of(plugin);
    return r ? arbor_param_get(params, PARAM_COUNT, r->values, id, out, r->error, sizeof r->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static arbor_status param_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    renderer *r = self_of(plugin);
    return r ? arbor_param_set(params, PARAM_COUNT, r->values, id, value, r->error, sizeof r->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static const arbor_params_v1 params_interface = {
    .count = param_count, .describe = param_describe, .get = param_get, .set = param_set};

static void destroy(arbor_plugin *plugin) { free(self_of(plugin)); }

static const void *get_interface(const arbor_plugin *plugin, const char *id)
{
    (void)plugin;
    if (id && strcmp(id, ARBOR_INTERFACE_RENDERER) == 0)
        return &renderer_interface;
    if (id && strcmp(id, ARBOR_INTERFACE_PARAMS) == 0)
        return &params_interface;
    return NULL;
}

static const char *last_error(const arbor_plugin *plugin)
{
    renderer *r = self_of(plugin);
    return r ? r->error : "not an instance";
}

static arbor_status init(const arbor_host *host, const char *library_path)
{
    (void)host;
    (void)library_path;
    return ARBOR_OK;
}

static void deinit(void) {}

static uint32_t plugin_count(void) { return 1; }

static const arbor_plugin_descriptor *plugin_descriptor(uint32_t index)
{
    return index == 0 ? &descriptor : NULL;
}

static arbor_status create_plugin(const arbor_host *host, const char *id, arbor_plugin **out)
{
    renderer *r;
    (void)host;
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!id)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    if (strcmp(id, descriptor.id) != 0)
        return ARBOR_ERROR_NOT_FOUND;
    r = (renderer *)calloc(1, sizeof *r);
    if (!r)
        return ARBOR_ERROR_OUT_OF_MEMORY;
    r->plugin.struct_size = sizeof(arbor_plugin);
    r->plugin.descriptor = &descriptor;
    r->plugin.plugin_data = r;
    r->plugin.destroy = destroy;
    r->plugin.get_interface = get_interface;
    r->plugin.last_error = last_error;
    arbor_param_reset(params, PARAM_COUNT, r->values);
    *out = &r->plugin;
    return ARBOR_OK;
}

ARBOR_PLUGIN_ENTRY = {
    .struct_size = sizeof(arbor_plugin_entry),
    .abi_version = ARBOR_ABI_VERSION_INIT,
    .init = init,
    .deinit = deinit,
    .plugin_count = plugin_count,
    .plugin_descriptor = plugin_descriptor,
    .create_plugin = create_plugin,
};
