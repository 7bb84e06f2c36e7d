/*
 * arbor/param_check.h - parameters for plugins written in C: values checked,
 * parsed and stored from their arbor_param_desc descriptions alone, so the
 * arbor.params/1 interface of a C plugin is a few lines.  Header-only C99;
 * not part of the ABI (the host never sees it), include it where you need it.
 *
 * The checks are the ones params.h demands of set() and `arbor plugin-check`
 * tries: ARBOR_ERROR_INVALID_ARGUMENT for a NULL or too small record, another
 * type or component count, NULL text; ARBOR_ERROR_OUT_OF_RANGE for NaN, a
 * number outside [min_value, max_value], a fraction for an INT, a BOOL other
 * than 0 or 1, a CHOICE index outside [0, choice_count - 1];
 * ARBOR_ERROR_NOT_FOUND for an unknown id.  Every function that takes a
 * message buffer leaves it "" on success and writes one sentence naming the
 * parameter and the problem on failure, so an instance's last_error buffer
 * can be passed straight in.
 *
 * Typical use, with the descriptions in a static array and one
 * arbor_param_slot per parameter in the instance:
 *
 *     static const arbor_param_desc my_params[] = {...};
 *     enum { MY_PARAM_COUNT = sizeof my_params / sizeof my_params[0] };
 *     typedef struct { arbor_plugin plugin; arbor_param_slot values[MY_PARAM_COUNT];
 *                      char error[256]; } my_instance;
 *
 *     create:  arbor_param_reset(my_params, MY_PARAM_COUNT, self->values);
 *     get:     return arbor_param_get(my_params, MY_PARAM_COUNT, self->values,
 *                                     id, out, self->error, sizeof self->error);
 *     set:     return arbor_param_set(my_params, MY_PARAM_COUNT, self->values,
 *                                     id, value, self->error, sizeof self->error);
 *     in use:  double gamma = self->values[MY_GAMMA].value.number[0];
 *
 * Define ARBOR_PARAM_TEXT_MAX before including to change the longest
 * STRING or PATH value a slot holds (4096 bytes with its NUL by default);
 * longer text is refused with ARBOR_ERROR_TOO_LARGE.
 */
#ifndef ARBOR_PARAM_CHECK_H
#define ARBOR_PARAM_CHECK_H

#include "params.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef ARBOR_PARAM_TEXT_MAX
#define ARBOR_PARAM_TEXT_MAX 4096
#endif

/* One parameter's current value; value.text points into `text` for STRING
 * and PATH. */
typedef struct arbor_param_slot {
    arbor_param_value value;
    char text[ARBOR_PARAM_TEXT_MAX];
} arbor_param_slot;

/* Empties msg (of msg_size bytes; msg may be NULL). */
static inline void arbor_param_clear(char *msg, size_t msg_size)
{
    if (msg && msg_size > 0)
        msg[0] = '\0';
}

/* Writes a message into msg (of msg_size bytes; msg may be NULL) and returns
 * status. */
static inline arbor_status arbor_param_fail(char *msg, size_t msg_size, arbor_status status, const char *id,
                                            const char *problem)
{
    if (msg && msg_size > 0)
        snprintf(msg, msg_size, "parameter '%s': %s", id ? id : "(null)", problem);
    return status;
}

/* Index of the description with this id among descs[0 .. count), or -1. */
static inline int32_t arbor_param_find(const arbor_param_desc *descs, uint32_t count, const char *id)
{
    uint32_t i;
    if (!descs || !id)
        return -1;
    for (i = 0; i < count; ++i)
        if (descs[i].id && strcmp(descs[i].id, id) == 0)
            return (int32_t)i;
    return -1;
}

/* The number of components a value of this description has. */
static inline uint32_t arbor_param_components(const arbor_param_desc *d)
{
    return (d->type == ARBOR_PARAM_FLOAT || d->type == ARBOR_PARAM_INT) ? d->components : 1u;
}

/* ARBOR_OK when `v` is a value `d` allows, else the status set() must answer,
 * with a message. */
static inline arbor_status arbor_param_check(const arbor_param_desc *d, const arbor_param_value *v, char *msg,
                                             size_t msg_size)
{
    uint32_t c, n;
    char problem[160];
    arbor_param_clear(msg, msg_size);
    if (!d)
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, "(null)", "no description");
    if (!v || v->struct_size < ARBOR_MIN_SIZE(arbor_param_value))
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id,
                                "the value record is NULL or too small");
    n = arbor_param_components(d);
    if (v->type != d->type || v->components != n) {
        snprintf(problem, sizeof problem, "expects type %u with %u component%s, got type %u with %u",
                 (unsigned)d->type, (unsigned)n, n == 1 ? "" : "s", (unsigned)v->type, (unsigned)v->components);
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, problem);
    }
    switch (d->type) {
    case ARBOR_PARAM_STRING:
    case ARBOR_PARAM_PATH:
        if (!v->text)
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, "the text is NULL");
        if (strlen(v->text) >= ARBOR_PARAM_TEXT_MAX) {
            snprintf(problem, sizeof problem, "the text is longer than %d bytes", ARBOR_PARAM_TEXT_MAX - 1);
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_TOO_LARGE, d->id, problem);
        }
        return ARBOR_OK;
    case ARBOR_PARAM_BOOL:
        if (v->number[0] != 0.0 && v->number[0] != 1.0)
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_OUT_OF_RANGE, d->id, "a boolean is 0 or 1");
        return ARBOR_OK;
    case ARBOR_PARAM_CHOICE:
        if (!(v->number[0] >= 0.0 && v->number[0] < (double)d->choice_count) ||
            v->number[0] != floor(v->number[0])) {
            snprintf(problem, sizeof problem, "choice %g is not an index in [0, %u]", v->number[0],
                     (unsigned)(d->choice_count ? d->choice_count - 1 : 0u));
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_OUT_OF_RANGE, d->id, problem);
        }
        return ARBOR_OK;
    case ARBOR_PARAM_FLOAT:
    case ARBOR_PARAM_INT:
        for (c = 0; c < n; ++c) {
            const double x = v->number[c];
            if (!(x >= d->min_value && x <= d->max_value)) { /* NaN fails too */
                snprintf(problem, sizeof problem, "%g lies outside [%g, %g]", x, d->min_value, d->max_value);
                return arbor_param_fail(msg, msg_size, ARBOR_ERROR_OUT_OF_RANGE, d->id, problem);
            }
            if (d->type == ARBOR_PARAM_INT && x != floor(x)) {
                snprintf(problem, sizeof problem, "%g is not a whole number", x);
                return arbor_param_fail(msg, msg_size, ARBOR_ERROR_OUT_OF_RANGE, d->id, problem);
            }
        }
        return ARBOR_OK;
    default:
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, "unknown parameter type");
    }
}

/* Stores `v` (checked first) into `slot`; on failure the slot keeps its
 * value.  Text is copied. */
static inline arbor_status arbor_param_store(const arbor_param_desc *d, arbor_param_slot *slot,
                                             const arbor_param_value *v, char *msg, size_t msg_size)
{
    uint32_t c;
    const arbor_status s = arbor_param_check(d, v, msg, msg_size);
    if (s != ARBOR_OK)
        return s;
    slot->value.struct_size = (uint32_t)sizeof(arbor_param_value);
    slot->value.type = d->type;
    slot->value.components = arbor_param_components(d);
    for (c = 0; c < ARBOR_PARAM_MAX_COMPONENTS; ++c)
        slot->value.number[c] = c < slot->value.components ? v->number[c] : 0.0;
    if (d->type == ARBOR_PARAM_STRING || d->type == ARBOR_PARAM_PATH) {
        memmove(slot->text, v->text, strlen(v->text) + 1);
        slot->value.text = slot->text;
    } else {
        slot->text[0] = '\0';
        slot->value.text = "";
    }
    return ARBOR_OK;
}

/* Every slot at its description's default (default_value, default_text). */
static inline void arbor_param_reset(const arbor_param_desc *descs, uint32_t count, arbor_param_slot *slots)
{
    uint32_t i, c;
    for (i = 0; i < count; ++i) {
        arbor_param_slot *s = &slots[i];
        const arbor_param_desc *d = &descs[i];
        memset(&s->value, 0, sizeof s->value);
        s->value.struct_size = (uint32_t)sizeof(arbor_param_value);
        s->value.type = d->type;
        s->value.components = arbor_param_components(d);
        for (c = 0; c < s->value.components && c < ARBOR_PARAM_MAX_COMPONENTS; ++c)
            s->value.number[c] = d->default_value[c];
        s->text[0] = '\0';
        if ((d->type == ARBOR_PARAM_STRING || d->type == ARBOR_PARAM_PATH) && d->default_text)
            snprintf(s->text, sizeof s->text, "%s", d->default_text);
        s->value.text = s->text;
    }
}

/* arbor_params_v1::get over descriptions and slots. */
static inline arbor_status arbor_param_get(const arbor_param_desc *descs, uint32_t count,
                                           const arbor_param_slot *slots, const char *id, arbor_param_value *out,
                                           char *msg, size_t msg_size)
{
    uint32_t c;
    int32_t i;
    arbor_param_clear(msg, msg_size);
    if (!id || !out || out->struct_size < ARBOR_MIN_SIZE(arbor_param_value))
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, id,
                                "get: NULL id, or a value record that is NULL or too small");
    i = arbor_param_find(descs, count, id);
    if (i < 0)
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_NOT_FOUND, id, "no such parameter");
    out->type = slots[i].value.type;
    out->components = slots[i].value.components;
    for (c = 0; c < ARBOR_PARAM_MAX_COMPONENTS; ++c)
        out->number[c] = slots[i].value.number[c];
    out->text = slots[i].value.text;
    return ARBOR_OK;
}

/* arbor_params_v1::set over descriptions and slots. */
static inline arbor_status arbor_param_set(const arbor_param_desc *descs, uint32_t count, arbor_param_slot *slots,
                                           const char *id, const arbor_param_value *value, char *msg,
                                           size_t msg_size)
{
    int32_t i;
    arbor_param_clear(msg, msg_size);
    if (!id)
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, id, "set: NULL id");
    i = arbor_param_find(descs, count, id);
    if (i < 0)
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_NOT_FOUND, id, "no such parameter");
    return arbor_param_store(&descs[i], &slots[i], value, msg, msg_size);
}

/* Parses text as people write values ("1.5", "64,64,32", "true", a choice
 * id) into *out, checked against the description.  STRING and PATH point
 * out->text at `text` itself.  For tests, tools and defaults given as
 * text; the host parses command lines itself. */
static inline arbor_status arbor_param_parse(const arbor_param_desc *d, const char *text, arbor_param_value *out,
                                             char *msg, size_t msg_size)
{
    uint32_t c, n;
    const char *p;
    char problem[160];
    arbor_param_clear(msg, msg_size);
    if (!d || !text || !out)
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d ? d->id : NULL,
                                "parse: NULL argument");
    memset(out, 0, sizeof *out);
    out->struct_size = (uint32_t)sizeof(arbor_param_value);
    out->type = d->type;
    n = out->components = arbor_param_components(d);
    out->text = "";
    switch (d->type) {
    case ARBOR_PARAM_STRING:
    case ARBOR_PARAM_PATH:
        out->text = text;
        break;
    case ARBOR_PARAM_BOOL:
        if (strcmp(text, "true") == 0 || strcmp(text, "1") == 0)
            out->number[0] = 1.0;
        else if (strcmp(text, "false") == 0 || strcmp(text, "0") == 0)
            out->number[0] = 0.0;
        else {
            snprintf(problem, sizeof problem, "'%.80s' is not true or false", text);
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, problem);
        }
        break;
    case ARBOR_PARAM_CHOICE:
        for (c = 0; c < d->choice_count; ++c)
            if (d->choices && d->choices[c] && strcmp(d->choices[c], text) == 0)
                break;
        if (c == d->choice_count) {
            snprintf(problem, sizeof problem, "'%.80s' is not one of its choices", text);
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, problem);
        }
        out->number[0] = (double)c;
        break;
    case ARBOR_PARAM_FLOAT:
    case ARBOR_PARAM_INT:
        p = text;
        for (c = 0; c < n; ++c) {
            char *end = NULL;
            out->number[c] = strtod(p, &end);
            if (end == p) {
                snprintf(problem, sizeof problem, "'%.80s' is not %u number%s separated by commas", text,
                         (unsigned)n, n == 1 ? "" : "s");
                return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, problem);
            }
            p = end;
            if (c + 1 < n) {
                if (*p != ',') {
                    snprintf(problem, sizeof problem, "'%.80s' is not %u numbers separated by commas", text,
                             (unsigned)n);
                    return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, problem);
                }
                ++p;
            }
        }
        if (*p != '\0') {
            snprintf(problem, sizeof problem, "'%.80s' has more than %u number%s", text, (unsigned)n,
                     n == 1 ? "" : "s");
            return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, problem);
        }
        break;
    default:
        return arbor_param_fail(msg, msg_size, ARBOR_ERROR_INVALID_ARGUMENT, d->id, "unknown parameter type");
    }
    return arbor_param_check(d, out, msg, msg_size);
}

#endif /* ARBOR_PARAM_CHECK_H */
