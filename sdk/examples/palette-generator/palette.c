/*
 * palette.c - an Arbor transfer-function generator in plain C: a fixed
 * palette, opacity by depth, and a cut given in physical units.
 *
 * Branch b gets colour palette[depth(b) mod 8] (the root the first) and a
 * ramp of opacity over its interval, from 0 at its saddle value to
 *
 *     alpha(b) = opacity * (depth(b) + 1) / (max depth + 1)
 *
 * at its extremum, so inner structures are more opaque than the ones around
 * them.  The root's function spans the whole value range.  Values below
 * `clear-below`, a physical value (HU for CT), stay transparent in every
 * branch: the generator thinks in physical units and turns them into stored
 * values with the tree's mapping (ABI 1.4), or the volume's on older hosts.
 *
 * Rules it follows (sdk/docs/contract.md): the lookup table (what renderers
 * use) and the control points (the editable form) describe the same
 * function: the points are its corners, ascending in value, and the table is
 * their linear interpolation, so an edited point can be rebaked faithfully.
 * Colours are straight sRGB.  The depiction is left to the host
 * (depiction_by_host), which applies opacity factors, hues and vividness
 * alike for every generator.  Points live in task->allocate memory, which
 * the host copies before the call ends.
 */
#include <arbor/arbor.h>
#include <arbor/param_check.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const arbor_plugin_descriptor descriptor = {
    .struct_size = sizeof(arbor_plugin_descriptor),
    .id = "org.arbor.example.palette",
    .kind = ARBOR_KIND_TF_GENERATOR,
    .name = "Fixed palette, opacity by depth (example)",
    .version = "1.0.0",
    .vendor = "Arbor",
    .description = "A fixed palette by depth, opacity rising with depth, transparent below a physical value. "
                   "Example of a transfer-function generator in plain C.",
    .url = "",
};

/* Straight sRGB, by depth (Okabe-Ito colours, told apart with colour vision
 * deficiencies). */
#define PALETTE_SIZE 8
static const float palette[PALETTE_SIZE][3] = {
    {0.60f, 0.60f, 0.60f}, {0.90f, 0.62f, 0.00f}, {0.34f, 0.71f, 0.91f}, {0.00f, 0.62f, 0.45f},
    {0.94f, 0.89f, 0.26f}, {0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.80f, 0.47f, 0.65f},
};

enum { OPACITY, CLEAR_BELOW, PARAM_COUNT };

static const arbor_param_desc params[PARAM_COUNT] = {
    [OPACITY] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "opacity",
                 .name = "Opacity", .group = "Opacity", .unit = "",
                 .hint = "Opacity at the extremum of the deepest branches; shallower ones get a share by depth",
                 .components = 1, .min_value = 0, .max_value = 1, .default_value = {0.8}, .default_text = ""},
    [CLEAR_BELOW] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "clear-below",
                     .name = "Clear below", .group = "Opacity", .unit = "physical",
                     .hint = "Physical values below this (HU for CT) stay transparent; -1e30 clears nothing",
                     .components = 1, .min_value = -1e30, .max_value = 1e30, .default_value = {-1e30},
                     .default_text = ""},
};

typedef struct generator {
    arbor_plugin plugin;
    arbor_param_slot values[PARAM_COUNT];
    char error[256];
} generator;

static generator *self_of(const arbor_plugin *p) { return p ? (generator *)p->plugin_data : NULL; }

static arbor_status fail(generator *g, arbor_status status, const char *message)
{
    snprintf(g->error, sizeof g->error, "%s", message);
    return status;
}

/* Opacity of a branch at value v: a ramp from 0 at `from` to `top` at `to`
 * (from < to or from > to: a basin ramps downwards), 0 below the cut. */
static float ramp(double v, double from, double to, double top, double cut)
{
    double t;
    if (v < cut)
        return 0.0f;
    t = to != from ? (v - from) / (to - from) : 1.0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return (float)(top * t);
}

static int by_value(const void *a, const void *b)
{
    const double x = ((const arbor_tf_point *)a)->value, y = ((const arbor_tf_point *)b)->value;
    return x < y ? -1 : (x > y ? 1 : 0);
}

static arbor_status generate(arbor_plugin *plugin, const arbor_tf_request *request, arbor_tf_set *out,
                             arbor_task *task)
{
    generator *g = self_of(plugin);
    const arbor_branch_tree *t;
    double scale, offset, cut, opacity;
    uint32_t b, i, max_depth = 0, used = 0;
    arbor_tf_point *points;
    if (!g)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    g->error[0] = '\0';
    if (!request || request->struct_size < ARBOR_MIN_SIZE(arbor_tf_request) || !request->tree ||
        request->tree->struct_size < ARBOR_MIN_SIZE(arbor_branch_tree) || !request->tree->depth ||
        !request->tree->saddle_value || !request->tree->extremum_value)
        return fail(g, ARBOR_ERROR_INVALID_ARGUMENT, "generate: NULL or malformed request or tree");
    if (!out || out->struct_size < ARBOR_MIN_SIZE(arbor_tf_set) || !out->domain || !out->lut ||
        !out->point_offsets || out->lut_size < 2)
        return fail(g, ARBOR_ERROR_INVALID_ARGUMENT, "generate: NULL or malformed output");
    if (!task || task->struct_size < ARBOR_MIN_SIZE(arbor_task))
        return fail(g, ARBOR_ERROR_INVALID_ARGUMENT, "generate: NULL task (the host always passes one)");
    t = request->tree;
    if (out->branch_count != t->branch_count)
        return fail(g, ARBOR_ERROR_INVALID_ARGUMENT, "generate: the output is not sized for the tree");

    /* Physical units: the tree's mapping (1.4), else the volume's, else none. */
    scale = 1.0;
    offset = 0.0;
    if (ARBOR_HAS_FIELD(arbor_branch_tree, t->struct_size, value_unit)) {
        scale = t->value_scale;
        offset = t->value_offset;
    } else if (request->volume && request->volume->struct_size >= ARBOR_MIN_SIZE(arbor_volume)) {
        scale = request->volume->value_scale;
        offset = request->volume->value_offset;
    }
    if (scale == 0.0)
        return fail(g, ARBOR_ERROR_INVALID_ARGUMENT, "generate: the value mapping has scale 0");
    cut = (g->values[CLEAR_BELOW].value.number[0] - offset) / scale;
    if (scale < 0.0)
        return fail(g, ARBOR_ERROR_UNSUPPORTED, "generate: a negative value scale (physical values falling as "
                                                "stored ones rise) is not handled by this example");
    opacity = g->values[OPACITY].value.number[0];

    for (b = 0; b < t->branch_count; ++b)
        if (t->depth[b] > max_depth)
            max_depth = t->depth[b];

    /* At most 4 corners a branch: both ends, the cut and its foot. */
    points = (arbor_tf_point *)task->allocate(task, (uint64_t)t->branch_count * 4 * sizeof *points);
    if (!points)
        return fail(g, ARBOR_ERROR_OUT_OF_MEMORY, "generate: the host refused memory for the control points");

    for (b = 0; b < t->branch_count; ++b) {
        /* The root spans the volume's whole range; a branch its saddle and
         * extremum values, the ramp rising towards the extremum. */
        const double from = b == 0 ? request->value_range[0] : t->saddle_value[b];
        const double to = b == 0 ? request->value_range[1] : t->extremum_value[b];
        const double lo = from < to ? from : to, hi = from < to ? to : from;
        const double top = opacity * (t->depth[b] + 1.0) / (max_depth + 1.0);
        const float *colour = palette[t->depth[b] % PALETTE_SIZE];
        float *lut = out->lut + (size_t)b * out->lut_size * 4;
        arbor_tf_point *p = points + used;
        uint32_t n = 0, k;
        if (b % 256 == 0 && task->progress(task, (double)b / t->branch_count, "palette"))
            return fail(g, ARBOR_ERROR_CANCELLED, "cancelled");
        out->domain[2 * b] = lo;
        out->domain[2 * b + 1] = hi;
        for (i = 0; i < out->lut_size; ++i) {
            const double v = lo + (hi - lo) * i / (out->lut_size - 1.0);
            lut[4 * i + 0] = colour[0];
            lut[4 * i + 1] = colour[1];
            lut[4 * i + 2] = colour[2];
            lut[4 * i + 3] = ramp(v, from, to, top, cut);
        }
        /* Corners of the function: the ends and, when the cut falls inside,
         * the cut (opacity jumps there: a point just below at 0). */
        p[n].value = lo;
        p[n++].rgba[3] = ramp(lo, from, to, top, cut);
        if (cut > lo && cut < hi) {
            p[n].value = nextafter(cut, -INFINITY);
            p[n++].rgba[3] = 0.0f;
            p[n].value = cut;
            p[n++].rgba[3] = ramp(cut, from, to, top, cut);
        }
        p[n].value = hi;
        p[n++].rgba[3] = ramp(hi, from, to, top, cut);
        qsort(p, n, sizeof *p, by_value);
        for (k = 0; k < n; ++k)
            memcpy(p[k].rgba, colour, 3 * sizeof(float));
        out->point_offsets[b] = used;
        used += n;
        if (out->notes && out->note_size > 1 &&
            ARBOR_HAS_FIELD(arbor_tf_set, out->struct_size, note_size))
            snprintf(out->notes + (size_t)b * out->note_size, out->note_size, "palette %u, depth %u: opacity %.2f",
                     (unsigned)(t->depth[b] % PALETTE_SIZE), (unsigned)t->depth[b], top);
    }
    out->point_offsets[t->branch_count] = used;
    out->points = points;
    /* The host applies the depiction (ABI 1.4); an older host ignores this
     * field, and this generator then shows no depiction. */
    if (ARBOR_HAS_FIELD(arbor_tf_set, out->struct_size, depiction_by_host))
        out->depiction_by_host = 1;
    return ARBOR_OK;
}

static const arbor_tf_generator_v1 generator_interface = {.generate = generate};

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
    generator *g = self_of(plugin);
    return g ? arbor_param_get(params, PARAM_COUNT, g->values, id, out, g->error, sizeof g->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static arbor_status param_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    generator *g = self_of(plugin);
    return g ? arbor_param_set(params, PARAM_COUNT, g->values, id, value, g->error, sizeof g->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static const arbor_params_v1 params_interface = {
    .count = param_count, .describe = param_describe, .get = param_get, .set = param_set};

static void destroy(arbor_plugin *plugin) { free(self_of(plugin)); }

static const void *get_interface(const arbor_plugin *plugin, const char *id)
{
    (void)plugin;
    if (id && strcmp(id, ARBOR_INTERFACE_TF_GENERATOR) == 0)
        return &generator_interface;
    if (id && strcmp(id, ARBOR_INTERFACE_PARAMS) == 0)
        return &params_interface;
    return NULL;
}

static const char *last_error(const arbor_plugin *plugin)
{
    generator *g = self_of(plugin);
    return g ? g->error : "not an instance";
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
    generator *g;
    (void)host;
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!id)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    if (strcmp(id, descriptor.id) != 0)
        return ARBOR_ERROR_NOT_FOUND;
    g = (generator *)calloc(1, sizeof *g);
    if (!g)
        return ARBOR_ERROR_OUT_OF_MEMORY;
    g->plugin.struct_size = sizeof(arbor_plugin);
    g->plugin.descriptor = &descriptor;
    g->plugin.plugin_data = g;
    g->plugin.destroy = destroy;
    g->plugin.get_interface = get_interface;
    g->plugin.last_error = last_error;
    arbor_param_reset(params, PARAM_COUNT, g->values);
    *out = &g->plugin;
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
