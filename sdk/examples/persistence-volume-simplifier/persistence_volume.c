/*
 * persistence_volume.c - an Arbor simplifier in plain C:
 *
 *     importance = persistence * volume^e
 *
 * on the measures relative to the root (so 1 is the whole volume and the
 * importance lies in [0, 1], the scale of `--threshold`).  e = 0 ranks by
 * persistence alone; e = 1 is the product, which keeps bright specks and
 * faint swells out at once; e = 0.5 (the default) lets volume count for less
 * than contrast.
 *
 * It also shows the rows of ABI 1.4: each row's extremum kind and values, and
 * the value mapping.  `polarity` keeps only peaks (bright structures, bone and
 * contrast in CT) or only basins, and `min-extremum` drops structures whose
 * extremum lies below a physical value (HU for CT), converted to stored values
 * once in prepare.  Under a 1.0-1.3 host the rows lack those fields and the
 * two parameters are refused in prepare, naming the reason.
 *
 * Rules it follows (sdk/docs/contract.md): prepare runs after the parameters
 * were set and before the importance calls of a run; importance is called
 * hundreds of thousands of times, one batch per saddle, so it allocates
 * nothing and logs nothing; every row's importance depends on that row alone;
 * the root's row (root_row) must get a finite value >= 0 like the others.
 */
#include <arbor/arbor.h>
#include <arbor/param_check.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const arbor_plugin_descriptor descriptor = {
    .struct_size = sizeof(arbor_plugin_descriptor),
    .id = "org.arbor.example.persistence-volume",
    .kind = ARBOR_KIND_SIMPLIFIER,
    .name = "Persistence x volume^e (example)",
    .version = "1.0.0",
    .vendor = "Arbor",
    .description = "Importance = relative persistence times relative volume to the power e; optionally peaks or "
                   "basins only, above a physical value. Example of a simplifier in plain C.",
    .url = "",
};

enum { EXPONENT, POLARITY, MIN_EXTREMUM, PARAM_COUNT };
enum { BOTH, PEAKS, BASINS };

static const char *const polarities[] = {"both", "peaks", "basins"};
static const char *const polarity_names[] = {"peaks and basins", "peaks only (bright structures)",
                                             "basins only (dark structures)"};

static const arbor_param_desc params[PARAM_COUNT] = {
    [EXPONENT] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "exponent",
                  .name = "Volume exponent e", .group = "", .unit = "",
                  .hint = "importance = persistence x volume^e, both relative to the root", .components = 1,
                  .min_value = 0.0, .max_value = 4.0, .default_value = {0.5}, .default_text = ""},
    [POLARITY] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_CHOICE, .id = "polarity",
                  .name = "Polarity", .group = "", .unit = "",
                  .hint = "Rank peaks and basins, or give one of them importance 0", .components = 1,
                  .min_value = 0, .max_value = 2, .default_value = {BOTH}, .choice_count = 3,
                  .choices = polarities, .choice_names = polarity_names, .default_text = ""},
    [MIN_EXTREMUM] = {.struct_size = sizeof(arbor_param_desc), .type = ARBOR_PARAM_FLOAT, .id = "min-extremum",
                      .name = "Lowest extremum", .group = "", .unit = "physical",
                      .hint = "Branches whose extremum lies below this physical value (HU for CT) get importance "
                              "0; -1e30 keeps all",
                      .components = 1, .min_value = -1e30, .max_value = 1e30, .default_value = {-1e30},
                      .default_text = ""},
};

typedef struct simplifier {
    arbor_plugin plugin;
    arbor_param_slot values[PARAM_COUNT];
    /* Found in prepare, used by every importance call of the run. */
    uint32_t persistence, volume, width;
    int prepared;
    int use_extrema;       /* the rows carry kinds and values (ABI 1.4) */
    double min_stored;     /* min-extremum as a stored value */
    int min_stored_is_max; /* a negative value scale turns "above" into "below" */
    char error[256];
} simplifier;

static simplifier *self_of(const arbor_plugin *p) { return p ? (simplifier *)p->plugin_data : NULL; }

static arbor_status fail(simplifier *s, arbor_status status, const char *message)
{
    snprintf(s->error, sizeof s->error, "%s", message);
    return status;
}

static int column(const arbor_measure_rows *schema, const char *id)
{
    uint32_t c;
    for (c = 0; c < schema->measure_count; ++c)
        if (schema->measure_ids[c] && strcmp(schema->measure_ids[c], id) == 0)
            return (int)c;
    return -1;
}

static arbor_status prepare(arbor_plugin *plugin, const arbor_measure_rows *schema)
{
    simplifier *s = self_of(plugin);
    int p, v;
    double min_physical;
    if (!s)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    s->error[0] = '\0';
    s->prepared = 0;
    if (!schema || schema->struct_size < ARBOR_MIN_SIZE(arbor_measure_rows) || !schema->measure_ids)
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "prepare: the schema is NULL, too small or has no ids");
    p = column(schema, ARBOR_MEASURE_PERSISTENCE);
    v = column(schema, ARBOR_MEASURE_VOLUME);
    if (p < 0 || v < 0)
        return fail(s, ARBOR_ERROR_NOT_FOUND, "the host provides no persistence or no volume measure");
    s->persistence = (uint32_t)p;
    s->volume = (uint32_t)v;
    s->width = schema->measure_count;

    s->use_extrema = ARBOR_HAS_FIELD(arbor_measure_rows, schema->struct_size, value_unit);
    min_physical = s->values[MIN_EXTREMUM].value.number[0];
    if (!s->use_extrema && (s->values[POLARITY].value.number[0] != BOTH || min_physical > -1e30))
        return fail(s, ARBOR_ERROR_UNSUPPORTED,
                    "polarity and min-extremum need a host of ABI 1.4 or later (rows with extremum values)");
    if (s->use_extrema) {
        if (schema->value_scale == 0.0)
            return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "the value mapping has scale 0");
        /* Physical -> stored once, here, not per row. */
        s->min_stored = (min_physical - schema->value_offset) / schema->value_scale;
        s->min_stored_is_max = schema->value_scale < 0.0;
    }
    s->prepared = 1;
    return ARBOR_OK;
}

static arbor_status importance(arbor_plugin *plugin, const arbor_measure_rows *rows, double *out)
{
    simplifier *s = self_of(plugin);
    uint32_t r;
    double e;
    int polarity;
    if (!s)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    s->error[0] = '\0';
    if (!rows || rows->struct_size < ARBOR_MIN_SIZE(arbor_measure_rows) || !out)
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "importance: NULL rows or out, or rows too small");
    if (!s->prepared || rows->measure_count != s->width)
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "importance: not prepared for these columns");
    if (rows->row_count > 0 && !rows->relative_measures)
        return fail(s, ARBOR_ERROR_INVALID_ARGUMENT, "importance: rows without values");
    e = s->values[EXPONENT].value.number[0];
    polarity = (int)s->values[POLARITY].value.number[0];
    for (r = 0; r < rows->row_count; ++r) {
        const double *m = rows->relative_measures + (size_t)r * s->width;
        double importance = m[s->persistence] * pow(m[s->volume], e);
        if (s->use_extrema && rows->extremum_kind && rows->extremum_value && (int32_t)r != rows->root_row) {
            const int peak = rows->extremum_kind[r] == ARBOR_EXTREMUM_MAXIMUM;
            const double x = rows->extremum_value[r];
            if ((polarity == PEAKS && !peak) || (polarity == BASINS && peak))
                importance = 0.0;
            if (s->min_stored_is_max ? x > s->min_stored : x < s->min_stored)
                importance = 0.0;
        }
        out[r] = importance >= 0.0 ? importance : 0.0; /* finite: relative measures lie in [0, 1] */
    }
    return ARBOR_OK;
}

static const arbor_simplifier_v1 simplifier_interface = {.prepare = prepare, .importance = importance};

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
    simplifier *s = self_of(plugin);
    return s ? arbor_param_get(params, PARAM_COUNT, s->values, id, out, s->error, sizeof s->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static arbor_status param_set(arbor_plugin *plugin, const char *id, const arbor_param_value *value)
{
    simplifier *s = self_of(plugin);
    return s ? arbor_param_set(params, PARAM_COUNT, s->values, id, value, s->error, sizeof s->error)
             : ARBOR_ERROR_INVALID_ARGUMENT;
}

static const arbor_params_v1 params_interface = {
    .count = param_count, .describe = param_describe, .get = param_get, .set = param_set};

static void destroy(arbor_plugin *plugin) { free(self_of(plugin)); }

static const void *get_interface(const arbor_plugin *plugin, const char *id)
{
    (void)plugin;
    if (id && strcmp(id, ARBOR_INTERFACE_SIMPLIFIER) == 0)
        return &simplifier_interface;
    if (id && strcmp(id, ARBOR_INTERFACE_PARAMS) == 0)
        return &params_interface;
    return NULL;
}

static const char *last_error(const arbor_plugin *plugin)
{
    simplifier *s = self_of(plugin);
    return s ? s->error : "not an instance";
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
    simplifier *s;
    (void)host;
    if (!out)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!id)
        return ARBOR_ERROR_INVALID_ARGUMENT;
    if (strcmp(id, descriptor.id) != 0)
        return ARBOR_ERROR_NOT_FOUND;
    s = (simplifier *)calloc(1, sizeof *s);
    if (!s)
        return ARBOR_ERROR_OUT_OF_MEMORY;
    s->plugin.struct_size = sizeof(arbor_plugin);
    s->plugin.descriptor = &descriptor;
    s->plugin.plugin_data = s;
    s->plugin.destroy = destroy;
    s->plugin.get_interface = get_interface;
    s->plugin.last_error = last_error;
    arbor_param_reset(params, PARAM_COUNT, s->values);
    *out = &s->plugin;
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
