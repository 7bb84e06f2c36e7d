/*
 * arbor/transfer_function.h - plugins that generate one transfer function per
 * branch from the branch tree (and optionally a depiction and the volume).
 *
 * A transfer function maps a stored scalar value to straight (not
 * premultiplied) sRGB colour and opacity.  Each branch gets its own, defined
 * over its value interval `domain`; values outside clamp to the ends.  The
 * editable form is a list of control points; the form renderers use is a
 * lookup table of lut_size entries spanning the domain evenly.
 *
 * Opacity is the opacity of a ray segment opacity_unit_distance millimetres
 * long; renderers correct it for their own sample distance d by
 * 1 - (1 - alpha)^(d / opacity_unit_distance).
 *
 * Generators run on the branch tree alone: regenerating after a parameter
 * change (flow rate, hue template) must not need the contour tree again.
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
    double value;  /* stored scalar value */
    float rgba[4]; /* straight sRGB colour and opacity, each in [0, 1] */
    uint32_t reserved0;
} arbor_tf_point;

typedef struct arbor_tf_request {
    uint32_t struct_size;
    uint32_t reserved0;
    const arbor_branch_tree *tree;
    const arbor_depiction *depiction; /* NULL when no depictor ran */
    /* The volume, for generators that look at values (histograms); NULL when
     * the host regenerates from the tree alone.  A generator that needs it
     * fails with ARBOR_ERROR_INVALID_ARGUMENT when it is NULL. */
    const arbor_volume *volume;
    double value_range[2]; /* stored min and max of the volume */
    double min_spacing;    /* smallest voxel spacing of the volume, mm */
} arbor_tf_request;

/* Output.  The host allocates domain, lut and point_offsets for branch_count
 * branches; the plugin fills them and sets `points` to memory it obtained from
 * task->allocate. */
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
} arbor_tf_set;

typedef struct arbor_tf_generator_v1 {
    arbor_status (*generate)(arbor_plugin *plugin, const arbor_tf_request *request,
                             arbor_tf_set *out, arbor_task *task);
} arbor_tf_generator_v1;

#endif /* ARBOR_TRANSFER_FUNCTION_H */
