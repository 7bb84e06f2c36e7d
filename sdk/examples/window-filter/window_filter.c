/*
 * window_filter.c - an Arbor filter plugin in plain C: clamp a volume to a
 * window of physical values.
 *
 * Windowing before the contour tree is built is useful on CT: clamping to,
 * say, [-200, 1500] HU flattens the noise in air and in metal artefacts, so
 * the tree keeps the structures and loses thousands of noise branches.
 *
 * The file is also the template for third-party plugins.  It shows
 *   - the one exported symbol (ARBOR_PLUGIN_ENTRY) and its descriptor,
 *   - an instance record with its own last-error message,
 *   - the parameters interface (arbor.params/1) through arbor/param_check.h,
 *   - the kind's interface (arbor.filter/1) with argument checks that make
 *     `arbor plugin-check` pass,
 *   - progress reporting and cancellation through the task.
 * sdk/docs/contract.md says who calls what, from which thread, and how long
 * every pointer lives.
 */
#include <arbor/arbor.h>
#include <arbor/param_check.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- descriptor ------------------------------------------------------------ */

static const arbor_plugin_descriptor window_descriptor = {
    .struct_size = sizeof(arbor_plugin_descriptor),
    .flags = ARBOR_PLUGIN_FLAG_NONE,
    .id = "org.arbor.example.window", /* reverse-DNS: never change it once released */
    .kind = ARBOR_KIND_FILTER,
    .name = "Window (clamp)",
    .version = "1.0.0",
    .vendor = "Arbor",
    .description = "Clamps physical values to [low, high] before the contour tree is built; "
                   "example of a plugin written in plain C.",
    .url = "",
};

/* ---- parameters ------------------------------------------------------------ */

enum { PARAM_LOW, PARAM_HIGH, PARAM_COUNT };

static const arbor_param_desc window_params[PARAM_COUNT] = {
    [PARAM_LOW] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "low",
                   .name = "Low", .group = "Window", .unit = "",
                   .hint = "Physical values below this become it (HU for CT)", .components = 1,
                   .min_value = -1e9, .max_value = 1e9, .default_value = {-1e9}, .default_text = ""},
    [PARAM_HIGH] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "high",
                    .name = "High", .group = "Window", .unit = "",
                    .hint = "Physical values above this become it (HU for CT)", .components = 1,
                    .min_value = -1e9, .max_value = 1e9, .default_value = {1e9}, .default_text = ""},
};

/* ---- instance -------------------------------------------------------------- */

typedef struct window_instance {
    arbor_plugin plugin; /* first member: the host holds a pointer to it */
    arbor_param_slot values[PARAM_COUNT];
    char error[512];
} window_instance;

static window_instance *instance_of(const arbor_plugin *plugin)
{
    return plugin ? (window_instance *)plugin->plugin_data : NULL;
}

/* Record the reason of a failure and return its status. */
static arbor_status fail(window_instance *self, arbor_status status, const char *message)
{
    snprintf(self->error, sizeof self->error, "%s", message);
    return status;
}

static uint32_t params_count(const arbor_plugin *plugin)
{
    (void)plugin;
    return PARAM_COUNT;
}

static const arbor_param_desc *params_describe(const arbor_plugin *plugin, uint32_t index)
{
    (void)plugin;
    return index < PARAM_COUNT ? &window_params[index] : NULL;
}

static arbor_status params_get(const arbor_plugin *plugin, const char *id, arbor_param_value *out)
{
    window_instance *self = instance_of(plugin);
    if (!self)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    return arbor_param_get(window_params, PARAM_COUNT, self->values, id, out, self->error, sizeof self->error);
}

static arbor_status params_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    window_instance *self = instance_of(plugin);
    if (!self)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    self->error[0] = '\0';
    return arbor_param_set(window_params, PARAM_COUNT, self->values, id, value, self->error, sizeof self->error);
}

static const arbor_params_v1 window_params_interface = {
    .count = params_count, .describe = params_describe, .get = params_get, .set = params_set};

/* ---- the filter ------------------------------------------------------------ */

static arbor_status check_volume(window_instance *self, const arbor_volume *v, const char *what)
{
    char message[160];
    int a;
    if (!v || v->struct_size < ARBOR_MIN_SIZE(arbor_volume) || !v->voxels) {
        snprintf(message, sizeof message, "%s volume is NULL, too small or has no voxels", what);
        return fail(self, ARBOR_ERROR_INVALID_ARGUMENT, message);
    }
    if (arbor_voxel_size(v->voxel_type) == 0) {
        snprintf(message, sizeof message, "%s volume has an unknown voxel type", what);
        return fail(self, ARBOR_ERROR_INVALID_ARGUMENT, message);
    }
    for (a = 0; a < 3; ++a)
        if (v->dims[a] <= 0) {
            snprintf(message, sizeof message, "%s volume has a dimension below 1", what);
            return fail(self, ARBOR_ERROR_INVALID_ARGUMENT, message);
        }
    return ARBOR_OK;
}

static arbor_status filter_output_type(arbor_plugin *plugin, const arbor_volume *input,
                                       arbor_voxel_type *out_type)
{
    window_instance *self = instance_of(plugin);
    if (!self)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    self->error[0] = '\0';
    if (!input || input->struct_size < ARBOR_MIN_SIZE(arbor_volume) || !out_type)
        return fail(self, ARBOR_ERROR_INVALID_ARGUMENT, "output_type: NULL argument");
    *out_type = input->voxel_type; /* windowing keeps the voxel type */
    return ARBOR_OK;
}

/* Smallest and largest value a voxel type holds. */
static void type_range(arbor_voxel_type type, double *min, double *max)
{
    switch (type) {
    case ARBOR_VOXEL_U8: *min = 0; *max = 255; break;
    case ARBOR_VOXEL_I8: *min = -128; *max = 127; break;
    case ARBOR_VOXEL_U16: *min = 0; *max = 65535; break;
    case ARBOR_VOXEL_I16: *min = -32768; *max = 32767; break;
    case ARBOR_VOXEL_U32: *min = 0; *max = 4294967295.0; break;
    case ARBOR_VOXEL_I32: *min = -2147483648.0; *max = 2147483647.0; break;
    case ARBOR_VOXEL_F32: *min = -3.4e38; *max = 3.4e38; break;
    default: *min = -1.7e308; *max = 1.7e308; break;
    }
}

/* Clamp one slice of any voxel type.  lo/hi are stored values inside the
 * type's range, so the casts below are exact. */
#define CLAMP_SLICE(T)                                                                          \
    do {                                                                                        \
        for (j = 0; j < ny; ++j)                                                                \
            for (i = 0; i < nx; ++i) {                                                          \
                const T x = *(const T *)(src + i * in->strides[0] + j * in->strides[1]);        \
                const double d = (double)x;                                                     \
                *(T *)(dst + i * out->strides[0] + j * out->strides[1]) =                       \
                    d < lo ? (T)lo : (d > hi ? (T)hi : x);                                      \
            }                                                                                   \
    } while (0)

static arbor_status filter_apply(arbor_plugin *plugin, const arbor_volume *in, arbor_volume *out,
                                 arbor_task *task)
{
    window_instance *self = instance_of(plugin);
    int64_t i, j, k, nx, ny, nz;
    double lo, hi, tmin, tmax;
    arbor_status s;
    if (!self)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    self->error[0] = '\0';
    if ((s = check_volume(self, in, "input")) != ARBOR_OK)
        return s;
    if ((s = check_volume(self, out, "output")) != ARBOR_OK)
        return s;
    if (in->dims[0] != out->dims[0] || in->dims[1] != out->dims[1] || in->dims[2] != out->dims[2] ||
        in->voxel_type != out->voxel_type)
        return fail(self, ARBOR_ERROR_INVALID_ARGUMENT, "input and output differ in dims or type");
    lo = self->values[PARAM_LOW].value.number[0];
    hi = self->values[PARAM_HIGH].value.number[0];
    if (lo > hi)
        return fail(self, ARBOR_ERROR_OUT_OF_RANGE, "low is above high");

    /* Physical window -> stored values (a negative scale swaps the ends). */
    lo = (lo - in->value_offset) / in->value_scale;
    hi = (hi - in->value_offset) / in->value_scale;
    if (lo > hi) {
        const double t = lo;
        lo = hi;
        hi = t;
    }
    /* Integer types cannot hold fractions: round the window inwards. */
    if (in->voxel_type != ARBOR_VOXEL_F32 && in->voxel_type != ARBOR_VOXEL_F64) {
        lo = ceil(lo);
        hi = floor(hi);
    }
    type_range(in->voxel_type, &tmin, &tmax);
    lo = lo < tmin ? tmin : (lo > tmax ? tmax : lo);
    hi = hi < tmin ? tmin : (hi > tmax ? tmax : hi);

    nx = in->dims[0];
    ny = in->dims[1];
    nz = in->dims[2];
    for (k = 0; k < nz; ++k) {
        const unsigned char *src = (const unsigned char *)in->voxels + k * in->strides[2];
        unsigned char *dst = (unsigned char *)out->voxels + k * out->strides[2];
        /* The host always passes a task (contract.md); other callers may not. */
        if (task && task->progress(task, (double)k / (double)nz, "windowing"))
            return fail(self, ARBOR_ERROR_CANCELLED, "cancelled");
        switch (in->voxel_type) {
        case ARBOR_VOXEL_U8: CLAMP_SLICE(uint8_t); break;
        case ARBOR_VOXEL_I8: CLAMP_SLICE(int8_t); break;
        case ARBOR_VOXEL_U16: CLAMP_SLICE(uint16_t); break;
        case ARBOR_VOXEL_I16: CLAMP_SLICE(int16_t); break;
        case ARBOR_VOXEL_U32: CLAMP_SLICE(uint32_t); break;
        case ARBOR_VOXEL_I32: CLAMP_SLICE(int32_t); break;
        case ARBOR_VOXEL_F32: CLAMP_SLICE(float); break;
        case ARBOR_VOXEL_F64: CLAMP_SLICE(double); break;
        default: return fail(self, ARBOR_ERROR_UNSUPPORTED, "unsupported voxel type");
        }
    }
    if (task)
        task->progress(task, 1.0, "windowing");
    return ARBOR_OK;
}

static const arbor_filter_v1 window_filter_interface = {.output_type = filter_output_type,
                                                        .apply = filter_apply};

/* ---- instance record functions --------------------------------------------- */

static void instance_destroy(arbor_plugin *plugin)
{
    free(instance_of(plugin));
}

static const void *instance_get_interface(const arbor_plugin *plugin, const char *id)
{
    (void)plugin;
    if (!id)
        return NULL;
    if (strcmp(id, ARBOR_INTERFACE_FILTER) == 0)
        return &window_filter_interface;
    if (strcmp(id, ARBOR_INTERFACE_PARAMS) == 0)
        return &window_params_interface;
    return NULL;
}

static const char *instance_last_error(const arbor_plugin *plugin)
{
    window_instance *self = instance_of(plugin);
    return self ? self->error : "not an instance";
}

/* ---- entry ----------------------------------------------------------------- */

static arbor_status entry_init(const arbor_host *host, const char *library_path)
{
    (void)host;
    (void)library_path;
    return ARBOR_OK;
}

static void entry_deinit(void) {}

static uint32_t entry_plugin_count(void)
{
    return 1;
}

static const arbor_plugin_descriptor *entry_plugin_descriptor(uint32_t index)
{
    return index == 0 ? &window_descriptor : NULL;
}

/* Cheap: the host creates instances only to read their parameters, too. */
static arbor_status entry_create_plugin(const arbor_host *host, const char *plugin_id, arbor_plugin **out)
{
    window_instance *self;
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!plugin_id)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    if (strcmp(plugin_id, window_descriptor.id) != 0)
        return ARBOR_ERROR_NOT_FOUND;
    self = (window_instance *)calloc(1, sizeof *self);
    if (!self) {
        if (host && host->log)
            host->log(host, ARBOR_LOG_ERROR, "window filter: out of memory");
        return ARBOR_ERROR_OUT_OF_MEMORY;
    }
    self->plugin.struct_size = sizeof(arbor_plugin);
    self->plugin.descriptor = &window_descriptor;
    self->plugin.plugin_data = self;
    self->plugin.destroy = instance_destroy;
    self->plugin.get_interface = instance_get_interface;
    self->plugin.last_error = instance_last_error;
    arbor_param_reset(window_params, PARAM_COUNT, self->values);
    *out = &self->plugin;
    return ARBOR_OK;
}

ARBOR_PLUGIN_ENTRY = {
    .struct_size = sizeof(arbor_plugin_entry),
    .abi_version = ARBOR_ABI_VERSION_INIT,
    .init = entry_init,
    .deinit = entry_deinit,
    .plugin_count = entry_plugin_count,
    .plugin_descriptor = entry_plugin_descriptor,
    .create_plugin = entry_create_plugin,
};
