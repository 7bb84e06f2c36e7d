/*
 * arbor/depictor.h - plugins that depict a relationship between branches
 * (inclusion, neighbouring) as per-branch modulations of the transfer
 * functions, plus an optional legend image.
 *
 * The host fills the output arrays with neutral values before the call (role
 * OTHER, opacity factors 1, hue NaN, saturation 1); a depictor changes what its
 * relationship needs.  Who applies the result, and how: a generator applies
 * it itself, or, since ABI 1.4, leaves it to the host (transfer_function.h,
 * depiction_by_host), which applies it as follows to every lookup-table entry
 * and control point of branch b at stored value v:
 *
 *   opacity   alpha *= f_s + (f_e - f_s) * clamp((v - s) / (e - s), 0, 1)
 *             with f_s, f_e the factors at the saddle and extremum and s, e
 *             the tree's saddle_value[b] and extremum_value[b] (the root: the
 *             global minimum and maximum; f_e when s == e);
 *   hue       when not NaN, the colour's HSV hue becomes it (its HSV
 *             saturation and value stay);
 *   vividness the colour's CIELAB chroma (D65) is multiplied by saturation[b]
 *             at its L* and CIELAB hue angle, and the result clamped to sRGB.
 *             Vividness is chroma relative to the pure hue's (ALGORITHMS
 *             6.12), so this multiplies it.
 *
 * The depiction and the legend are separate pipeline stages with an
 * instance each, so two instances of a depictor may run at the same time.
 */
#ifndef ARBOR_DEPICTOR_H
#define ARBOR_DEPICTOR_H

#include "branch_tree.h"
#include "host.h"
#include "image.h"
#include "plugin.h"

#define ARBOR_INTERFACE_DEPICTOR "arbor.depictor/1"

/* Role of a branch with respect to the selected branch. */
typedef uint32_t arbor_branch_role;
#define ARBOR_ROLE_OTHER 0u
#define ARBOR_ROLE_SELECTED 1u
#define ARBOR_ROLE_PARENT 2u
#define ARBOR_ROLE_CHILD 3u
#define ARBOR_ROLE_SIBLING 4u
#define ARBOR_ROLE_ANCESTOR 5u   /* includes the selected branch, not its parent */
#define ARBOR_ROLE_DESCENDANT 6u /* included by the selected branch, not a child */

/* [borrowed: until return], the tree with it. */
typedef struct arbor_depiction_request {
    uint32_t struct_size;
    int32_t selected_branch; /* branch index, or -1 when nothing is selected */
    const arbor_branch_tree *tree;
} arbor_depiction_request;
#define ARBOR_MIN_SIZE_arbor_depiction_request ARBOR_SIZE_THROUGH(arbor_depiction_request, tree) /* through ABI 1.0 */

/* Output.  Every array has tree->branch_count entries and is [host-owned];
 * write into it during the call only. */
typedef struct arbor_depiction {
    uint32_t struct_size;
    uint32_t branch_count;
    arbor_branch_role *role;
    /* Opacity factors in [0, 1] at the branch's saddle value and at its
     * extremum value; in between the factor is linear in the scalar value.
     * Continuous depictions set a branch's saddle factor to its parent's
     * factor at that value. */
    float *opacity_at_saddle;
    float *opacity_at_extremum;
    /* Hue in degrees [0, 360) the branch must get, or NaN to leave the choice
     * to the transfer-function generator. */
    float *hue;
    /* Multiplier in [0, 1] of the branch's vividness (1 = unchanged). */
    float *saturation;
} arbor_depiction;
#define ARBOR_MIN_SIZE_arbor_depiction ARBOR_SIZE_THROUGH(arbor_depiction, saturation) /* through ABI 1.0 */

typedef struct arbor_depictor_v1 {
    /* Compute the depiction for the request into *out.  Called again when
     * the selection, the cut or a parameter changes.  [instance] */
    arbor_status (*depict)(arbor_plugin *plugin, const arbor_depiction_request *request,
                           arbor_depiction *out, arbor_task *task);

    /* *related = non-zero when branch a stands in this depictor's relationship
     * to branch b (inclusion: b is a proper ancestor of a; neighbouring: a is
     * b's parent, child or sibling).  A pure function of the tree: Arbor
     * itself does not call it at present (plugin-check does; tools may).
     * ARBOR_ERROR_INVALID_ARGUMENT when a or b >= branch_count.  [instance]
     * [cheap] [borrowed: tree until return] */
    arbor_status (*related)(arbor_plugin *plugin, const arbor_branch_tree *tree, uint32_t a,
                            uint32_t b, arbor_bool32 *related);

    /* Draw the legend (e.g. the relation wheel) into the host's image of the
     * size the host chose (Arbor: a square, 512 pixels unless the user says
     * otherwise; premultiplied as image.h says; depth and label_visibility
     * NULL).  Write every pixel: Arbor zero-fills the image, other callers
     * (plugin-check) do not.  ARBOR_ERROR_UNSUPPORTED when the depictor has
     * none.  Called on the legend stage's own instance.  [instance] */
    arbor_status (*legend)(arbor_plugin *plugin, const arbor_depiction_request *request,
                           arbor_image *out, arbor_task *task);
} arbor_depictor_v1;

#endif /* ARBOR_DEPICTOR_H */
