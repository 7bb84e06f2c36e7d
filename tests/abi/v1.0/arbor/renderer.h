/*
 * arbor/renderer.h - plugins that render a classified volume into an image.
 *
 * Classification is label-aware: a sample takes the transfer function of the
 * branch its voxel belongs to (label map), so equal values in different
 * structures can get different colours.  Sampling, shading and quality
 * settings are the renderer's own parameters (params.h).
 *
 * Renderers may cache data derived from the volume and labels between calls
 * (gradients, occupancy).  The revision counters in the request change
 * whenever the contents behind the pointers change.
 */
#ifndef ARBOR_RENDERER_H
#define ARBOR_RENDERER_H

#include "branch_tree.h"
#include "host.h"
#include "image.h"
#include "plugin.h"
#include "transfer_function.h"
#include "volume.h"

#define ARBOR_INTERFACE_RENDERER "arbor.renderer/1"

typedef uint32_t arbor_projection;
#define ARBOR_PROJECTION_PERSPECTIVE 1u
#define ARBOR_PROJECTION_ORTHOGRAPHIC 2u

/* A camera in the LPS millimetre frame of the volume. */
typedef struct arbor_camera {
    uint32_t struct_size;
    arbor_projection projection;
    double position[3];
    double focal_point[3];
    double view_up[3];     /* need not be orthogonal to the view direction */
    double view_angle;     /* perspective: vertical field of view, degrees */
    double parallel_scale; /* orthographic: half the viewport height, mm */
} arbor_camera;

typedef struct arbor_render_request {
    uint32_t struct_size;
    uint32_t reserved0;
    const arbor_volume *volume;
    const arbor_label_map *labels;           /* NULL: every voxel uses function 0 */
    const arbor_tf_set *transfer_functions;  /* one per label */
    const arbor_camera *camera;
    float background[4];                     /* straight sRGB + alpha behind the volume */
    uint64_t volume_revision;                /* changes when voxel values change */
    uint64_t labels_revision;                /* changes when labels change */
} arbor_render_request;

typedef struct arbor_renderer_v1 {
    /* Render into *out (size chosen by the host).  Report progress per row
     * block; honour cancellation. */
    arbor_status (*render)(arbor_plugin *plugin, const arbor_render_request *request,
                           arbor_image *out, arbor_task *task);
} arbor_renderer_v1;

#endif /* ARBOR_RENDERER_H */
