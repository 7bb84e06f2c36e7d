/*
 * arbor/branch_tree.h - the branch decomposition of a contour tree, its
 * per-branch measures, and the voxel -> branch label map it induces.
 *
 * A branch is a monotone path in the contour tree from a saddle to an extremum.
 * Branch 0 is the root: it runs from the global minimum (its "saddle" fields)
 * to the global maximum.  Every other branch hangs off its parent branch at
 * its saddle.  Parents come before their children (parent[b] < b).
 *
 * Measures describe the region a branch encloses at its saddle: the voxels
 * beyond the saddle's contour on the branch's side, the saddle included, and
 * so every branch simplified into it and every descendant.  They come as a
 * table: measure_count columns named by measure_ids, one row per branch.
 * The host provides at least the five ARBOR_MEASURE_* columns from
 * persistence to relative-hypervolume (simplifiers get exactly these); trees
 * handed to depictors and generators may have more (thickness, compactness).
 * relative_measures divides each column by the root's value (0 where the
 * root's is 0), so relative values lie in [0, 1] and do not change as the
 * tree is simplified.  The root's region is the whole volume.
 *
 * Values (saddle_value, extremum_value) are stored voxel values, not physical
 * ones; since ABI 1.4 the record carries the mapping to physical values.
 * Positions are LPS millimetres (see volume.h).  Vertices are voxel indices
 * i + nx*(j + ny*k).  The root's saddle is the global minimum and its
 * extremum the global maximum, kind ARBOR_EXTREMUM_MAXIMUM.
 *
 * The record is an input: [borrowed: until return], every array with it.
 */
#ifndef ARBOR_BRANCH_TREE_H
#define ARBOR_BRANCH_TREE_H

#include "abi.h"

/* Measure column ids. */
#define ARBOR_MEASURE_PERSISTENCE "persistence" /* |f(extremum) - f(saddle)| */
#define ARBOR_MEASURE_VOLUME "volume"           /* voxels in the region */
#define ARBOR_MEASURE_VOLUME_MM3 "volume-mm3"   /* the same in mm^3 */
/* Sum over the region of f - f_min (f_min: global minimum of the volume). */
#define ARBOR_MEASURE_HYPERVOLUME "hypervolume"
/* Volume between f and the saddle level: the sum over the region of
 * f - f(saddle) for a peak, f(saddle) - f for a basin, at least 0 (Carr's
 * hypervolume).  It is the sum of |f - f(saddle)| unless the region holds pits
 * below a peak's saddle level or bumps above a basin's, which count against it. */
#define ARBOR_MEASURE_RELATIVE_HYPERVOLUME "relative-hypervolume"
/* Since ABI 1.1, where the host has the simplified tree's label map: the
 * thickness, in mm, of the voxels labelled with the branch at the current
 * cut (its children's excluded): twice their volume over the area of their
 * boundary with other labels.  A shell (skin, skull) is as thick as the
 * shell, a ball of radius r 2r/3.  Look the column up by id; it may be
 * missing. */
#define ARBOR_MEASURE_THICKNESS "thickness-mm"
/* Since ABI 1.1, beside the thickness: the thickness over the cube root of
 * the labelled voxels' volume, about 0.4 for a ball, 0.25 for a long vessel,
 * below 0.1 for a shell such as the skull. */
#define ARBOR_MEASURE_COMPACTNESS "compactness"

typedef uint32_t arbor_extremum_kind;
#define ARBOR_EXTREMUM_MAXIMUM 1u /* the branch rises from its saddle */
#define ARBOR_EXTREMUM_MINIMUM 2u /* the branch falls from its saddle */

typedef struct arbor_branch_tree {
    uint32_t struct_size;
    uint32_t branch_count; /* >= 1 */
    uint32_t measure_count;
    uint32_t reserved0;

    const int32_t *parent;         /* [branch_count]; -1 for the root */
    const uint32_t *depth;         /* [branch_count]; root 0, child = parent + 1 */
    const uint32_t *child_offsets; /* [branch_count + 1]: children of b are */
    const uint32_t *children;      /*   children[child_offsets[b] .. child_offsets[b+1]) */

    const arbor_extremum_kind *extremum_kind; /* [branch_count] */
    const int64_t *saddle_vertex;             /* [branch_count] */
    const int64_t *extremum_vertex;           /* [branch_count]; identifies a branch */
    const double *saddle_value;               /* [branch_count] */
    const double *extremum_value;             /* [branch_count] */
    const double *saddle_position;            /* [3 * branch_count] */
    const double *extremum_position;          /* [3 * branch_count] */

    const char *const *measure_ids;  /* [measure_count] */
    const double *measures;          /* [branch_count * measure_count], row per branch */
    const double *relative_measures; /* same layout, each column / the root's */

    /* [branch_count] importance the simplifier gave each branch when the tree
     * was cut, or NULL when the tree was not simplified (the root's is 1).
     * [nullable] */
    const double *importance;

    /* Since ABI 1.4 (check ARBOR_HAS_FIELD(arbor_branch_tree, tree->struct_size,
     * value_unit)): the volume's mapping from stored values to physical ones,
     * physical = stored * value_scale + value_offset, and the physical unit
     * ("HU"; "" when unknown), as in arbor_volume.  The host always sets
     * them (scale 1, offset 0 when the file says nothing). */
    double value_scale;
    double value_offset;
    const char *value_unit;
} arbor_branch_tree;
#define ARBOR_MIN_SIZE_arbor_branch_tree ARBOR_SIZE_THROUGH(arbor_branch_tree, importance) /* through ABI 1.0 */

/* Which branch every voxel belongs to at the current simplification level:
 * labels are branch indices into the arbor_branch_tree it was cut with. */
typedef struct arbor_label_map {
    uint32_t struct_size;
    uint32_t label_count; /* = branch_count; every label is < label_count */
    int64_t dims[3];      /* the volume's dims */
    const uint32_t *labels; /* contiguous, i fastest */

    /* Since ABI 1.6 (check ARBOR_HAS_FIELD(arbor_label_map, map->struct_size,
     * saddle_value)): how the labels nest, so that a renderer can resolve a
     * label per sample instead of taking its nearest voxel's (topology-
     * controlled volume rendering, Weber et al. 2007).  parent[l] is the
     * label of l's parent branch (-1 for the root, label 0; parent[l] < l
     * otherwise), saddle_value[l] the stored value of l's saddle (the root's:
     * the volume's minimum).  The region of label l is bounded by the
     * isosurface at saddle_value[l].  Both [label_count]; they change with
     * the labels (labels_revision).  NULL when the host does not have the
     * tree the labels were cut with: then take the nearest voxel's label.
     * [nullable] */
    const int32_t *parent;
    const double *saddle_value;
} arbor_label_map;
#define ARBOR_MIN_SIZE_arbor_label_map ARBOR_SIZE_THROUGH(arbor_label_map, labels) /* through ABI 1.0 */

#endif /* ARBOR_BRANCH_TREE_H */
