/*
 * arbor/simplifier.h - plugins that rank branches by importance.
 *
 * The host owns the one decomposition engine; a simplifier only says how
 * important a branch is given its measures, so two simplifiers differ in
 * nothing but the importance they assign and can be compared fairly on one
 * tree.  The engine sweeps the contour tree twice, from the global minimum
 * up (the join tree: basins) and from the global maximum down (the split
 * tree: peaks).  Wherever two or more components of the swept region meet at
 * a saddle, each component is a candidate branch: its extremum and the region
 * beyond the saddle on its side.  The host asks the simplifier for the
 * importance of every candidate at that saddle; the most important one
 * continues through the saddle, the others end there as branches hanging off
 * it (ties: the older extremum continues; the component of the sweep's global
 * extremum always continues).  The resulting hierarchy is cut by importance:
 * `--threshold T` keeps the branches whose importance is > T, `--keep N` the
 * N most important (the root always), and without either `arbor run` keeps
 * the count at the knee of the log-importance curve.
 *
 * Importance scale.  T lies in [0, 1], with the root's relative measures 1:
 * return importance on that scale (1 = as important as the whole volume),
 * as the built-in simplifiers do by combining relative measures.  Larger
 * numbers are allowed and are kept at every threshold; 0 is kept by no
 * threshold and left out of the knee (which reads log importance).
 *
 * Rows are independent.  A batch holds the candidates meeting at one saddle
 * (2 or more rows) while the host decomposes, or up to 4096 branches of a
 * decomposition made earlier (by another simplifier, too) when the host
 * compares simplifiers (`arbor compare`, the workstation's priority lines).
 * The importance of a row must depend on that row and the parameters alone:
 * never on the other rows of the batch, their order or the calls before.
 *
 * The root's row.  While decomposing, the component of the sweep's global
 * extremum may be one of the candidates; its row carries the root's measures
 * (every relative measure 1).  The host ignores its importance but still
 * checks it, so it must be finite and >= 0 like every other.  Since ABI 1.4
 * root_row names it.  Batches of finished branches hold no root row.
 *
 * Depth is not offered: while the host decomposes, the hierarchy (and so
 * every branch's parent and depth) is what the importances decide.
 */
#ifndef ARBOR_SIMPLIFIER_H
#define ARBOR_SIMPLIFIER_H

#include "branch_tree.h"
#include "plugin.h"

#define ARBOR_INTERFACE_SIMPLIFIER "arbor.simplifier/1"

/* Measures of a batch of branches: row r, column c is measures[r *
 * measure_count + c]; the columns are named by measure_ids (the five
 * ARBOR_MEASURE_* columns from persistence to relative-hypervolume, in an
 * order to look up in prepare).  The record and every array it points to are
 * [borrowed: until return]. */
typedef struct arbor_measure_rows {
    uint32_t struct_size;
    uint32_t row_count;
    uint32_t measure_count;
    uint32_t reserved0;
    const char *const *measure_ids;  /* [measure_count] */
    const double *measures;          /* [row_count * measure_count] absolute */
    const double *relative_measures; /* same layout, each column / the root's */

    /* Since ABI 1.4 (check ARBOR_HAS_FIELD(arbor_measure_rows,
     * rows->struct_size, value_unit)): the extremum of every row, for
     * importances that look at values (prefer bright structures, ignore
     * basins).  NULL in the schema prepare gets (row_count 0).  Within one
     * decomposition batch every row has the same kind: maxima in the sweep
     * from the top, minima in the sweep from the bottom. */
    const arbor_extremum_kind *extremum_kind; /* [row_count] */
    const double *saddle_value;   /* [row_count] stored value where the row's region begins */
    const double *extremum_value; /* [row_count] stored value of the row's extremum */
    /* The row standing for the root's component (its importance is
     * ignored), or -1; -1 in the schema. */
    int32_t root_row;
    uint32_t reserved1;
    /* physical = stored * value_scale + value_offset, unit value_unit ("HU";
     * "" when unknown), as in arbor_volume.  Set in the schema too, so
     * prepare can turn a parameter given in physical units into stored
     * values once. */
    double value_scale;
    double value_offset;
    const char *value_unit;
} arbor_measure_rows;
#define ARBOR_MIN_SIZE_arbor_measure_rows ARBOR_SIZE_THROUGH(arbor_measure_rows, relative_measures) /* through ABI 1.0 */

typedef struct arbor_simplifier_v1 {
    /* Called once before every decomposition or comparison run, after the
     * parameters were set (they do not change until the run's last importance
     * call).  `schema` names the columns (its row_count is 0).  Look up the
     * columns the importance needs and fail with ARBOR_ERROR_NOT_FOUND,
     * naming the measure, if one is missing.  [instance]
     * [borrowed: schema until return] */
    arbor_status (*prepare)(arbor_plugin *plugin, const arbor_measure_rows *schema);

    /* Importance of each row: out[r] for row r, every one of them (the host
     * presets NaN and refuses what is left).  Must be finite and >= 0; larger
     * means more important (kept longer).  Called once per saddle where
     * branches meet, hundreds of thousands of times on a noisy scan, always
     * after prepare and from one thread at a time: keep it fast and free of
     * allocation and logging.  The columns are those of the schema.
     * [instance] [cheap] [borrowed: rows until return] [host-owned: out] */
    arbor_status (*importance)(arbor_plugin *plugin, const arbor_measure_rows *rows, double *out);
} arbor_simplifier_v1;

#endif /* ARBOR_SIMPLIFIER_H */
