/*
 * arbor/simplifier.h - plugins that rank branches by importance.
 *
 * The host owns the one pruning engine: it repeatedly removes the least
 * important leaf branch, merges its region into the branch it hangs off, and
 * updates that branch's measures.  A simplifier only says how important a
 * branch is given its current measures, so two simplifiers differ in nothing
 * but the importance they assign and can be compared fairly on one tree.
 */
#ifndef ARBOR_SIMPLIFIER_H
#define ARBOR_SIMPLIFIER_H

#include "branch_tree.h"
#include "plugin.h"

#define ARBOR_INTERFACE_SIMPLIFIER "arbor.simplifier/1"

/* Measures of a batch of branches: row r, column c is measures[r *
 * measure_count + c]; the columns are named by measure_ids (the same columns
 * as arbor_branch_tree). */
typedef struct arbor_measure_rows {
    uint32_t struct_size;
    uint32_t row_count;
    uint32_t measure_count;
    uint32_t reserved0;
    const char *const *measure_ids;  /* [measure_count] */
    const double *measures;          /* [row_count * measure_count] absolute */
    const double *relative_measures; /* same layout, each column / the root's */
} arbor_measure_rows;
#define ARBOR_MIN_SIZE_arbor_measure_rows ARBOR_SIZE_THROUGH(arbor_measure_rows, relative_measures) /* through ABI 1.0 */

typedef struct arbor_simplifier_v1 {
    /* Called once before a pruning run.  `schema` names the columns (its
     * row_count is 0).  Look up the columns the importance needs and fail with
     * ARBOR_ERROR_NOT_FOUND, naming the measure, if one is missing. */
    arbor_status (*prepare)(arbor_plugin *plugin, const arbor_measure_rows *schema);

    /* Importance of each row: out[r] for row r.  Must be finite and >= 0;
     * larger means more important (kept longer).  Called many times during a
     * run, always from one thread; keep it fast and free of allocation. */
    arbor_status (*importance)(arbor_plugin *plugin, const arbor_measure_rows *rows, double *out);
} arbor_simplifier_v1;

#endif /* ARBOR_SIMPLIFIER_H */
