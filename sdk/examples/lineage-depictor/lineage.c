/*
 * lineage.c - an Arbor depictor in plain C: the selected branch's line of
 * descent (its ancestors up to the root and every branch below it) stays as
 * the generator made it; every other branch fades to `fade` of its opacity
 * and `fade-saturation` of its vividness.  The selected branch can be given
 * a hue of its own.  The legend draws the line from the root (top) down to
 * the selected branch, one bar per level.
 *
 * Rules it follows (sdk/docs/contract.md): the host fills the output with
 * neutral values (factors 1, hue NaN, saturation 1, role OTHER) and the
 * depictor changes only what its relationship needs; nothing selected
 * (selected_branch -1) leaves everything neutral.  It only describes the
 * depiction: the generator, or the host for generators that leave it to the
 * host (ABI 1.4), applies it.  related() is a pure function of the tree.
 */
#include <arbor/arbor.h>
#include <arbor/param_check.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const arbor_plugin_descriptor descriptor = {
    .struct_size = sizeof(arbor_plugin_descriptor),
    .id = "org.arbor.example.lineage",
    .kind = ARBOR_KIND_DEPICTOR,
    .name = "Line of descent (example)",
    .version = "1.0.0",
    .vendor = "Arbor",
    .description = "The selected branch, its ancestors and its descendants stay as they are; every other branch "
                   "fades. Example of a depictor in plain C.",
    .url = "",
};

enum { FADE, FADE_SATURATION, HUE, PARAM_COUNT };

static const arbor_param_desc params[PARAM_COUNT] = {
    [FADE] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "fade", .name = "Fade",
              .group = "", .unit = "", .hint = "Opacity factor of branches outside the line of descent",
              .components = 1, .min_value = 0, .max_value = 1, .default_value = {0.2}, .default_text = ""},
    [FADE_SATURATION] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT,
                         .id = "fade-saturation", .name = "Fade saturation", .group = "", .unit = "",
                         .hint = "Vividness factor of branches outside the line of descent", .components = 1,
                         .min_value = 0, .max_value = 1, .default_value = {0.3}, .default_text = ""},
    [HUE] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "hue",
             .name = "Hue of the selection", .group = "", .unit = "degrees",
             .hint = "HSV hue the selected branch gets; -1 leaves its colour to the generator", .components = 1,
             .min_value = -1, .max_value = 359, .default_value = {-1}, .default_text = ""},
};

typedef struct depictor {
    arbor_plugin plugin;
    arbor_param_slot values[PARAM_COUNT];
    char error[256];
} depictor;

static depictor *self_of(const arbor_plugin *p) { return p ? (depictor *)p->plugin_data : NULL; }

static arbor_status fail(depictor *d, arbor_status status, const char *message)
{
    snprintf(d->error, sizeof d->error, "%s", message);
    return status;
}

static int valid_tree(const arbor_branch_tree *t)
{
    return t && t->struct_size >= ARBOR_MIN_SIZE(arbor_branch_tree) && t->branch_count >= 1 && t->parent &&
           t->depth;
}

/* True when `ancestor` lies on the path from `b` up to the root (b itself
 * included).  Parents come before children, so the walk ends. */
static int within(const arbor_branch_tree *t, uint32_t b, uint32_t ancestor)
{
    int32_t x = (int32_t)b;
    while (x >= 0 && (uint32_t)x > ancestor)
        x = t->parent[x];
    return x >= 0 && (uint32_t)x == ancestor;
}

static arbor_status depict(arbor_plugin *plugin, const arbor_depiction_request *request, arbor_depiction *out,
                           arbor_task *task)
{
    depictor *d = self_of(plugin);
    const arbor_branch_tree *t;
    uint32_t b, s;
    float fade, fade_saturation;
    double hue;
    (void)task;
    if (!d)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    d->error[0] = '\0';
    if (!request || request->struct_size < ARBOR_MIN_SIZE(arbor_depiction_request) || !valid_tree(request->tree))
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "depict: NULL or malformed request or tree");
    if (!out || out->struct_size < ARBOR_MIN_SIZE(arbor_depiction) || !out->role || !out->opacity_at_saddle ||
        !out->opacity_at_extremum || !out->hue || !out->saturation)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "depict: NULL or malformed output");
    t = request->tree;
    if (out->branch_count != t->branch_count)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "depict: the output is not sized for the tree");
    if (request->selected_branch < 0)
        return ARBOR_OK; /* nothing selected: the host's neutral values stand */
    s = (uint32_t)request->selected_branch;
    if (s >= t->branch_count)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "depict: the selected branch is not in the tree");
    fade = (float)d->values[FADE].value.number[0];
    fade_saturation = (float)d->values[FADE_SATURATION].value.number[0];
    hue = d->values[HUE].value.number[0];
    for (b = 0; b < t->branch_count; ++b) {
        if (b == s) {
            out->role[b] = ARBOR_ROLE_SELECTED;
            if (hue >= 0)
                out->hue[b] = (float)hue;
        } else if (t->parent[s] >= 0 && b == (uint32_t)t->parent[s]) {
            out->role[b] = ARBOR_ROLE_PARENT;
        } else if (within(t, s, b)) {
            out->role[b] = ARBOR_ROLE_ANCESTOR;
        } else if (t->parent[b] >= 0 && (uint32_t)t->parent[b] == s) {
            out->role[b] = ARBOR_ROLE_CHILD;
        } else if (within(t, b, s)) {
            out->role[b] = ARBOR_ROLE_DESCENDANT;
        } else {
            out->opacity_at_saddle[b] = fade;
            out->opacity_at_extremum[b] = fade;
            out->saturation[b] = fade_saturation;
        }
    }
    return ARBOR_OK;
}

static arbor_status related(arbor_plugin *plugin, const arbor_branch_tree *tree, uint32_t a, uint32_t b,
                            arbor_bool32 *is_related)
{
    depictor *d = self_of(plugin);
    if (!d)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    d->error[0] = '\0';
    if (!valid_tree(tree) || !is_related)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "related: NULL or malformed tree, or NULL out");
    if (a >= tree->branch_count || b >= tree->branch_count)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "related: branch index out of range");
    *is_related = a != b && (within(tree, a, b) || within(tree, b, a));
    return ARBOR_OK;
}

/* Fills rows [y0, y1) of the image with a premultiplied colour, with margins. */
static void bar(arbor_image *img, uint32_t y0, uint32_t y1, const float rgb[3], float alpha)
{
    uint32_t x, y;
    const uint32_t margin = img->width / 10;
    for (y = y0; y < y1 && y < img->height; ++y)
        for (x = margin; x + margin < img->width; ++x) {
            float *p = img->rgba + (int64_t)y * img->row_stride + 4 * (int64_t)x;
            p[0] = rgb[0] * alpha;
            p[1] = rgb[1] * alpha;
            p[2] = rgb[2] * alpha;
            p[3] = alpha;
        }
}

/* Straight sRGB of an HSV hue at full saturation and value. */
static void hue_rgb(double hue, float rgb[3])
{
    const double h = fmod(hue, 360.0) / 60.0, x = 1.0 - fabs(fmod(h, 2.0) - 1.0);
    const int sector = (int)h;
    const double r[6] = {1, x, 0, 0, x, 1}, g[6] = {x, 1, 1, x, 0, 0}, bl[6] = {0, 0, x, 1, 1, x};
    rgb[0] = (float)r[sector % 6];
    rgb[1] = (float)g[sector % 6];
    rgb[2] = (float)bl[sector % 6];
}

static arbor_status legend(arbor_plugin *plugin, const arbor_depiction_request *request, arbor_image *out,
                           arbor_task *task)
{
    depictor *d = self_of(plugin);
    const float white[3] = {0.9f, 0.9f, 0.9f}, grey[3] = {0.5f, 0.5f, 0.5f};
    float selected[3];
    uint32_t levels, level, step, s;
    double hue;
    (void)task;
    if (!d)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    d->error[0] = '\0';
    if (!request || request->struct_size < ARBOR_MIN_SIZE(arbor_depiction_request) || !valid_tree(request->tree))
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "legend: NULL or malformed request or tree");
    if (!out || out->struct_size < ARBOR_MIN_SIZE(arbor_image) || !out->rgba || out->width < 8 || out->height < 8 ||
        out->row_stride < 4 * (int64_t)out->width)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "legend: NULL or malformed image (at least 8 x 8)");
    if (request->selected_branch >= (int32_t)request->tree->branch_count)
        return fail(d, ARBOR_ERROR_INVALID_ARGUMENT, "legend: the selected branch is not in the tree");
    /* Every pixel is written: transparent first, then the bars. */
    for (level = 0; level < out->height; ++level)
        memset(out->rgba + (int64_t)level * out->row_stride, 0, 4 * sizeof(float) * out->width);
    s = request->selected_branch < 0 ? 0u : (uint32_t)request->selected_branch;
    hue = d->values[HUE].value.number[0];
    hue_rgb(hue >= 0 ? hue : 30.0, selected);
    /* One bar per level of the line from the root to the selection, and one
     * faded bar for the branches outside it. */
    levels = request->tree->depth[s] + 2;
    step = out->height / levels;
    if (step < 2)
        return fail(d, ARBOR_ERROR_UNSUPPORTED, "legend: the image is too small for this line of descent");
    for (level = 0; level + 1 < levels; ++level)
        bar(out, level * step + step / 4, (level + 1) * step - step / 4, level + 2 == levels ? selected : white,
            1.0f);
    bar(out, (levels - 1) * step + step / 4, levels * step - step / 4, grey,
        (float)d->values[FADE].value.number[0]);
    return ARBOR_OK;
}

static const arbor_depictor_v1 depictor_interface = {.depict = depict, .related = related, .legend = legend};

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
    depictor *d = self_of(plugin);
    return d ? arbor_param_get(params, PARAM_COUNT, d->values, id, out, d->error, sizeof d->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static arbor_status param_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    depictor *d = self_of(plugin);
    return d ? arbor_param_set(params, PARAM_COUNT, d->values, id, value, d->error, sizeof d->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static const arbor_params_v1 params_interface = {
    .count = param_count, .describe = param_describe, .get = param_get, .set = param_set};

static void destroy(arbor_plugin *plugin) { free(self_of(plugin)); }

static const void *get_interface(const arbor_plugin *plugin, const char *id)
{
    (void)plugin;
    if (id && strcmp(id, ARBOR_INTERFACE_DEPICTOR) == 0)
        return &depictor_interface;
    if (id && strcmp(id, ARBOR_INTERFACE_PARAMS) == 0)
        return &params_interface;
    return NULL;
}

static const char *last_error(const arbor_plugin *plugin)
{
    depictor *d = self_of(plugin);
    return d ? d->error : "not an instance";
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
    depictor *d;
    (void)host;
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!id)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    if (strcmp(id, descriptor.id) != 0)
        return ARBOR_ERROR_NOT_FOUND;
    d = (depictor *)calloc(1, sizeof *d);
    if (!d)
        return ARBOR_ERROR_OUT_OF_MEMORY;
    d->plugin.struct_size = sizeof(arbor_plugin);
    d->plugin.descriptor = &descriptor;
    d->plugin.plugin_data = d;
    d->plugin.destroy = destroy;
    d->plugin.get_interface = get_interface;
    d->plugin.last_error = last_error;
    arbor_param_reset(params, PARAM_COUNT, d->values);
    *out = &d->plugin;
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
