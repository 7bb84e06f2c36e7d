/*
 * arbor/params.h - parameters a plugin describes and the host sets.
 *
 * A plugin describes its parameters as data (id, type, range, default, unit,
 * group, hint).  From these descriptions alone the host builds command-line
 * flags, GUI panels and the parameter section of session files, so no plugin
 * needs host code of its own.  Values live in the instance: the host sets them
 * before a call and reads them back to save a session.
 *
 * When values change.  Never during a call.  Before every job that uses an
 * instance (a generation, a frame, a pruning run) the host sets every
 * parameter again, on the thread that then makes the job's calls, so a value
 * may differ from one call to the next (a slider moved between two frames);
 * within a job it stays put (a simplifier's values are the same from prepare
 * to its last importance call).  A value a plugin derives from its
 * parameters is derived in the call that uses it, or again whenever set()
 * changes one.  Settings are first checked on a fresh instance of their own
 * (set, then get to read every value back); that instance does no work.
 * arbor/param_check.h validates and parses values from these descriptions.
 *
 * Interface id: ARBOR_INTERFACE_PARAMS.  Optional: an instance without it has
 * no parameters.
 */
#ifndef ARBOR_PARAMS_H
#define ARBOR_PARAMS_H

#include "plugin.h"

#define ARBOR_INTERFACE_PARAMS "arbor.params/1"

typedef uint32_t arbor_param_type;
#define ARBOR_PARAM_FLOAT 1u  /* 1..4 doubles (components) */
#define ARBOR_PARAM_INT 2u    /* 1..4 integers, carried in doubles (|n| < 2^53) */
#define ARBOR_PARAM_BOOL 3u   /* number[0] is 0 or 1 */
#define ARBOR_PARAM_CHOICE 4u /* number[0] is an index into choices */
#define ARBOR_PARAM_STRING 5u /* text */
#define ARBOR_PARAM_PATH 6u   /* text naming a file (GUIs show a file picker) */

#define ARBOR_PARAM_MAX_COMPONENTS 4

typedef uint32_t arbor_param_flags;
#define ARBOR_PARAM_FLAG_NONE 0u
/* Only shown in the advanced section of a panel. */
#define ARBOR_PARAM_FLAG_ADVANCED (1u << 0)
/* Sliders use a logarithmic scale (min_value must be > 0). */
#define ARBOR_PARAM_FLAG_LOG_SCALE (1u << 1)
/* A FLOAT with 3 or 4 components in [0, 1] is an sRGB(A) colour. */
#define ARBOR_PARAM_FLAG_COLOR (1u << 2)
/* No meaningful default: the host refuses to run the plugin until the user
 * sets it (e.g. the dimensions of a headerless raw file). */
#define ARBOR_PARAM_FLAG_REQUIRED (1u << 3)

typedef struct arbor_param_desc {
    uint32_t struct_size;
    arbor_param_type type;
    /* Stable id: lowercase letters, digits and '-', starting with a letter,
     * unique within the plugin.  Becomes a CLI flag and a session key. */
    const char *id;
    const char *name;  /* label, e.g. "Flow rate" */
    const char *group; /* panel group, e.g. "Opacity"; "" for none */
    const char *unit;  /* "mm", "HU", "%", ""... */
    const char *hint;  /* one sentence of help: CLI --help and tooltips */
    uint32_t components; /* FLOAT, INT: 1..4; every other type: 1 */
    arbor_param_flags flags;
    /* FLOAT, INT: inclusive bounds, the same for every component. */
    double min_value;
    double max_value;
    /* FLOAT, INT: per component; BOOL: 0 or 1; CHOICE: default index. */
    double default_value[ARBOR_PARAM_MAX_COMPONENTS];
    /* CHOICE: number of choices and their stable ids ("ramp", "hat"), plus
     * optional labels (NULL: the ids are shown). */
    uint32_t choice_count;
    uint32_t reserved0;
    const char *const *choices;
    const char *const *choice_names;
    /* STRING, PATH: default text ("" for none). */
    const char *default_text;
} arbor_param_desc;
#define ARBOR_MIN_SIZE_arbor_param_desc ARBOR_SIZE_THROUGH(arbor_param_desc, default_text) /* through ABI 1.0 */

typedef struct arbor_param_value {
    uint32_t struct_size;
    arbor_param_type type; /* must match the description */
    uint32_t components;   /* must match the description */
    uint32_t reserved0;
    double number[ARBOR_PARAM_MAX_COMPONENTS]; /* FLOAT, INT, BOOL, CHOICE */
    const char *text;                          /* STRING, PATH */
} arbor_param_value;
#define ARBOR_MIN_SIZE_arbor_param_value ARBOR_SIZE_THROUGH(arbor_param_value, text) /* through ABI 1.0 */

typedef struct arbor_params_v1 {
    /* Number of parameters of the instance; constant for its life.
     * [instance] [cheap] */
    uint32_t (*count)(const arbor_plugin *plugin);

    /* Description of parameter `index` (< count), valid for the life of the
     * instance, or NULL when index is out of range.  The host keeps the
     * pointers and reads them from other threads while the instance lives:
     * they must not change.  [instance] [cheap] */
    const arbor_param_desc *(*describe)(const arbor_plugin *plugin, uint32_t index);

    /* Current value of parameter `id`.  out->text stays valid until the next
     * set() or destroy().  ARBOR_ERROR_NOT_FOUND for an unknown id.  Set
     * out->type and out->components; the host set out->struct_size.
     * [instance] [borrowed: id until return] */
    arbor_status (*get)(const arbor_plugin *plugin, const char *id, arbor_param_value *out);

    /* Set parameter `id`.  The value is checked against its description:
     * ARBOR_ERROR_NOT_FOUND (unknown id), ARBOR_ERROR_INVALID_ARGUMENT (type
     * or component count differ, NULL text), ARBOR_ERROR_OUT_OF_RANGE
     * (outside [min, max], not an integer, choice index too large, NaN).  On
     * error the previous value is kept.  value->text is copied.
     * [instance] [borrowed: id, value and value->text until return] */
    arbor_status (*set)(arbor_plugin *plugin, const char *id, const arbor_param_value *value);
} arbor_params_v1;

#endif /* ARBOR_PARAMS_H */
