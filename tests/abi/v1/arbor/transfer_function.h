/*
 * arbor/transfer_function.h - plugins that generate one transfer function per
 * branch from the branch tree (and optionally a depiction and the volume).
 *
 * A transfer function maps a stored scalar value to straight (not
 * premultiplied), display-encoded sRGB colour and opacity, each in [0, 1].
 * Each branch gets its own, defined over its value interval `domain`; values
 * outside clamp to the ends.  Branch b's function colours the voxels labelled
 * b, so the root's (label 0: everything not in a kept branch) should span
 * the whole value range, request->value_range, as the built-in generators'
 * do; another branch's usually spans its saddle and extremum values.  To
 * think in physical units (HU), map with the tree's value_scale and
 * value_offset (ABI 1.4; request->volume carries them too).
 *
 * Two forms.  The lookup table (lut_size RGBA entries spanning the domain
 * evenly, entry i at domain[0] + (domain[1] - domain[0]) * i / (lut_size - 1))
 * is what every renderer uses.  The control points are the editable form:
 * per branch, in non-decreasing value (the host refuses others), read as
 * linear in value between points and constant beyond the first and the last.
 * They need not reproduce the table exactly (a table may hold curves the
 * points only sketch), but a person editing points must see the edit: when a
 * transfer-function file's points of a branch were changed, Arbor rebakes
 * that branch's table from them.
 *
 * Opacity is the opacity of a ray segment opacity_unit_distance millimetres
 * long; renderers correct it for their own sample distance d by
 * 1 - (1 - alpha)^(d / opacity_unit_distance).
 *
 * After generation the host may scale a branch's optical depth (visibility
 * balancing: alpha' = 1 - (1 - alpha)^m, tables and points alike) and apply a
 * person's per-branch edits of visibility, opacity and colour (to the
 * tables); renderers see the result.
 *
 * Generators run on the branch tree alone: regenerating after a parameter
 * change (flow rate, hue template) must not need the contour tree again.
 * The host calls generate again on every such change (every slider move).
 */
#ifndef ARBOR_TRANSFER_FUNCTION_H
#define ARBOR_TRANSFER_FUNCTION_H

#include "branch_tree.h"
#include "depictor.h"
#include "host.h"
#include "plugin.h"
#include "volume.h"

#define ARBOR_INTERFACE_TF_GENERATOR "arbor.tf-generator/1"

typedef struct arbor_tf_point {
    double value;  /* stored scalar value, finite */
    float rgba[4]; /* straight sRGB colour and opacity, each in [0, 1] */
    uint32_t reserved0;
    uint32_t reserved1; /* 0; the tail padding, named (ABI 1.3) */
} arbor_tf_point;

/* [borrowed: until return], with everything it points to. */
typedef struct arbor_tf_request {
    uint32_t struct_size;
    uint32_t reserved0;
    const arbor_branch_tree *tree;
    /* The depictor's result, or NULL when no depictor ran (`--relation
     * none`; Arbor's default is the inclusion depictor).  [nullable] */
    const arbor_depiction *depiction;
    /* The volume, for generators that look at values (histograms).  Arbor
     * passes it on every call; a host may pass NULL when it regenerates from
     * the tree alone, and a generator that needs it then fails with
     * ARBOR_ERROR_INVALID_ARGUMENT.  [nullable] */
    const arbor_volume *volume;
    double value_range[2]; /* stored min and max of the volume (the root's saddle and extremum values) */
    double min_spacing;    /* smallest voxel spacing of the volume, mm */
    /* Since ABI 1.1 (check ARBOR_HAS_FIELD(arbor_tf_request, struct_size,
     * background_level)): stored values at or below this are the scan's
     * background (the air around a CT, the dark noise around an MR), which
     * should stay transparent.  background_peak is the background's most
     * frequent value, below the level: the distance between the two is the
     * width of its noise.  The host found no background when the level is
     * NaN or not above the peak (a zero-filled request has none). */
    double background_level;
    double background_peak;
} arbor_tf_request;
#define ARBOR_MIN_SIZE_arbor_tf_request ARBOR_SIZE_THROUGH(arbor_tf_request, min_spacing) /* through ABI 1.0 */

/* Output.  The host allocates domain, lut and point_offsets for branch_count
 * branches (zero-filled, [host-owned]); the plugin fills every one of them
 * and sets `points` to memory it obtained from task->allocate (NULL when
 * there are none); the host copies the points before the task ends.  The
 * host refuses non-finite or inverted domains, table or point values outside
 * [0, 1], decreasing offsets, points out of value order. */
typedef struct arbor_tf_set {
    uint32_t struct_size;
    uint32_t branch_count;
    uint32_t lut_size; /* entries per branch, chosen by the host, >= 2 */
    uint32_t reserved0;
    double opacity_unit_distance; /* mm; the host presets request->min_spacing */
    double *domain;               /* [2 * branch_count]: low, high value of each LUT */
    float *lut;                   /* [branch_count * lut_size * 4] straight RGBA */
    uint32_t *point_offsets;      /* [branch_count + 1]: points of branch b are */
    arbor_tf_point *points;       /*   points[point_offsets[b] .. point_offsets[b+1]) */
    /* Since ABI 1.1 (check ARBOR_HAS_FIELD(arbor_tf_set, struct_size,
     * note_size)): NULL, or note_size bytes per branch, zero-filled by the
     * host, where a generator may say in one NUL-terminated UTF-8 line why
     * a branch's function looks as it does ("hat: a thin shell, 2.1 mm
     * thick").  Reports show them. */
    char *notes;
    uint32_t note_size;
    uint32_t reserved1;
    /* Since ABI 1.4 (check ARBOR_HAS_FIELD(arbor_tf_set, out->struct_size,
     * depiction_by_host)): 0 when the host calls.  A generator that sets it
     * to 1 leaves request->depiction alone (it may read the roles) and the
     * host applies the depiction to the table and the points after the call,
     * with the formulas of depictor.h, so every generator shows a
     * relationship alike.  A generator that leaves it 0 applies the
     * depiction itself (or, like the histogram baseline, deliberately not). */
    arbor_bool32 depiction_by_host;
    uint32_t reserved2;
} arbor_tf_set;
#define ARBOR_MIN_SIZE_arbor_tf_set ARBOR_SIZE_THROUGH(arbor_tf_set, points) /* through ABI 1.0 */

typedef struct arbor_tf_generator_v1 {
    /* One function per branch of request->tree into *out.  [instance]
     * [borrowed: request until return] */
    arbor_status (*generate)(arbor_plugin *plugin, const arbor_tf_request *request,
                             arbor_tf_set *out, arbor_task *task);
} arbor_tf_generator_v1;

#endif /* ARBOR_TRANSFER_FUNCTION_H */
