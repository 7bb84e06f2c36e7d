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
 * whenever the contents behind the pointers change.  The pointers themselves
 * are [borrowed: until return]: keep copies or derived data, keyed by the
 * revisions, never the pointers.  One instance renders the pipeline's frames
 * (the workstation's previews and passes too); a turntable, the choice of
 * the default renderer and the workstation's frames drawn into its OpenGL
 * context (arbor.renderer-gl/1) use instances of their own.
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
#define ARBOR_MIN_SIZE_arbor_camera ARBOR_SIZE_THROUGH(arbor_camera, parallel_scale) /* through ABI 1.0 */

typedef struct arbor_render_request {
    uint32_t struct_size;
    uint32_t reserved0;
    const arbor_volume *volume;
    const arbor_label_map *labels;           /* NULL: every voxel uses function 0 (previews before the tree exists) [nullable] */
    const arbor_tf_set *transfer_functions;  /* one per label */
    const arbor_camera *camera;
    float background[4];                     /* straight sRGB + alpha behind the volume */
    uint64_t volume_revision;                /* changes when voxel values change */
    uint64_t labels_revision;                /* changes when labels change */
} arbor_render_request;
#define ARBOR_MIN_SIZE_arbor_render_request ARBOR_SIZE_THROUGH(arbor_render_request, labels_revision) /* through ABI 1.0 */

typedef struct arbor_renderer_v1 {
    /* Render into *out (size chosen by the host; rgba [host-owned], depth
     * and label_visibility as image.h says).  Report progress per row block;
     * honour cancellation.  [instance] [borrowed: request until return] */
    arbor_status (*render)(arbor_plugin *plugin, const arbor_render_request *request,
                           arbor_image *out, arbor_task *task);
} arbor_renderer_v1;

/* ------------------------------------------------------------------------
 * arbor.renderer/2 (since ABI 1.2): rendering for interaction.  A renderer
 * may offer /1, /2 or both; the host uses /2 when it is there and keeps
 * serving renderers that offer /1 alone (full frames, one pass).
 *
 * Tiles.  The host asks for a region of a full frame of frame_width x
 * frame_height pixels (the frame the camera spans); *out is region-sized,
 * its pixel (0, 0) is frame pixel (region_x, region_y), and row_stride and
 * depth_stride let it sit inside the host's frame buffer.  A region's
 * pixels are exactly the frame's pixels there: tiles rendered separately
 * join without seams.
 *
 * Passes.  ARBOR_RENDER_PASS_FULL is the full-quality image.
 * ARBOR_RENDER_PASS_COARSE is fast enough to answer a dragged slider or
 * mouse: fewer rays (the renderer fills every pixel of the region, e.g. by
 * spreading each ray over a block of pixels) and larger steps.
 * ARBOR_RENDER_PASS_SUPERSAMPLE refines a full image while the user is
 * idle: *out holds the image after sample_index - 1 refinements (the full
 * pass's for sample_index 1), and the renderer blends in one more sample per
 * pixel, offset within the pixel and along the ray, as
 * out = (sample_index * out + sample) / (sample_index + 1).  A renderer
 * without a coarse or supersample pass renders FULL for COARSE and returns
 * ARBOR_ERROR_UNSUPPORTED for SUPERSAMPLE.  A coarse pass may choose its
 * rays anew for each frame (from the time earlier frames took), but only at
 * a call whose region starts at (0, 0): a host rendering a frame in tiles
 * starts with that one, and its tiles agree.
 *
 * Revisions.  Each revision changes whenever the contents behind its
 * pointer change (and only then, for the host's cache to work): a renderer
 * compares them to decide what to rebuild and never needs to hash lookup
 * tables.  0 means unknown: treat the contents as changed.
 *
 * Labels per sample (since ABI 1.6).  The label map may say how its labels
 * nest (arbor_label_map.parent and .saddle_value).  A renderer that reads
 * them resolves the label of a sample whose cell has corners of different
 * labels by the sample's interpolated value: from the label of a corner
 * below the value and of one above it, walk up the tree, the deeper of the
 * two at a time, until one's saddle lies between the value and its corner
 * (that one) or the two meet.  Boundaries between structures are then the
 * isosurfaces at their saddle values instead of walls of voxels.  A renderer
 * that ignores them takes each sample's nearest voxel's label, as before.
 *
 * Visibility (label_visibility in *out): summed over the region's pixels;
 * the host adds up its tiles.  For SUPERSAMPLE, over the new samples.
 *
 * Cancellation.  When task->cancelled turns true the renderer returns
 * ARBOR_ERROR_CANCELLED soon (within a tile's rows, not at the end of the
 * frame).  Then each pixel of the region holds either its contents before
 * the call or its final value for this pass, never a partial value, depth
 * likewise; label_visibility is undefined.
 *
 * Threads.  The host calls one instance from one thread at a time (see
 * plugin.h), not always from the same thread: the pipeline runs each render
 * as a job.  A renderer that needs a thread of its own (an OpenGL context
 * is current on one thread) keeps one inside the plugin and hands each call
 * to it.  A renderer may run worker threads within a call and keep them
 * between calls; the task's callbacks may be called from any of them.
 * ------------------------------------------------------------------------ */
#define ARBOR_INTERFACE_RENDERER_2 "arbor.renderer/2"

typedef uint32_t arbor_render_pass;
#define ARBOR_RENDER_PASS_FULL 0u
#define ARBOR_RENDER_PASS_COARSE 1u
#define ARBOR_RENDER_PASS_SUPERSAMPLE 2u

typedef struct arbor_render_request_v2 {
    uint32_t struct_size;
    arbor_render_pass pass;
    const arbor_volume *volume;
    const arbor_label_map *labels;          /* NULL: every voxel uses function 0 */
    const arbor_tf_set *transfer_functions; /* one per label */
    const arbor_camera *camera;
    float background[4];                    /* straight sRGB + alpha behind the volume */
    uint64_t volume_revision;               /* voxel values */
    uint64_t labels_revision;               /* the label map */
    uint64_t transfer_functions_revision;   /* domains, lookup tables, opacity unit distance */
    uint32_t frame_width, frame_height;     /* the full frame, > 0 */
    uint32_t region_x, region_y;            /* the region: within the frame, */
    uint32_t region_width, region_height;   /* out->width x out->height */
    uint32_t sample_index;                  /* SUPERSAMPLE: 1, 2, ...; else 0 */
    uint32_t reserved0;
} arbor_render_request_v2;
#define ARBOR_MIN_SIZE_arbor_render_request_v2 ARBOR_SIZE_THROUGH(arbor_render_request_v2, reserved0) /* through ABI 1.2 */

typedef struct arbor_renderer_v2 {
    uint32_t struct_size;
    uint32_t reserved0;
    /* Render `request->pass` of the request's region into *out.
     * [instance] [borrowed: request until return] */
    arbor_status (*render)(arbor_plugin *plugin, const arbor_render_request_v2 *request,
                           arbor_image *out, arbor_task *task);
} arbor_renderer_v2;
#define ARBOR_MIN_SIZE_arbor_renderer_v2 ARBOR_SIZE_THROUGH(arbor_renderer_v2, render) /* through ABI 1.2 */

/* ------------------------------------------------------------------------
 * arbor.render-device/1 (since ABI 1.2): what a renderer renders on, so
 * the host can choose between renderers and say why.  Optional; a renderer
 * without it counts as rendering on the CPU.  An OpenGL renderer on Mesa's
 * llvmpipe or softpipe (graphics emulated on the CPU, slower than a CPU ray
 * caster) says ARBOR_DEVICE_SOFTWARE_GPU.
 * ------------------------------------------------------------------------ */
#define ARBOR_INTERFACE_RENDER_DEVICE "arbor.render-device/1"

typedef uint32_t arbor_device_kind;
#define ARBOR_DEVICE_CPU 1u          /* the CPU's cores */
#define ARBOR_DEVICE_GPU 2u          /* graphics hardware */
#define ARBOR_DEVICE_SOFTWARE_GPU 3u /* a graphics API emulated on the CPU */

typedef struct arbor_render_device {
    uint32_t struct_size;
    arbor_device_kind kind;
    /* One line for people, e.g. "NVIDIA H200/PCIe/SSE2, OpenGL 4.6" or
     * "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5"; valid for the life
     * of the instance. */
    const char *name;
} arbor_render_device;
#define ARBOR_MIN_SIZE_arbor_render_device ARBOR_SIZE_THROUGH(arbor_render_device, name) /* through ABI 1.2 */

typedef struct arbor_render_device_v1 {
    uint32_t struct_size;
    uint32_t reserved0;
    /* [instance]; may be slow the first time (an OpenGL renderer makes its
     * context), so the host asks once per process. */
    arbor_status (*describe)(const arbor_plugin *plugin, arbor_render_device *out);
} arbor_render_device_v1;
#define ARBOR_MIN_SIZE_arbor_render_device_v1 ARBOR_SIZE_THROUGH(arbor_render_device_v1, describe) /* through ABI 1.2 */

/* ------------------------------------------------------------------------
 * arbor.renderer-gl/1 (since ABI 1.5): rendering into the host's OpenGL
 * context, so that a workstation shows a frame without reading it back to
 * the CPU and uploading it again.  Optional, for renderers that draw with
 * OpenGL and also offer arbor.renderer/2 (which stays the way to images on
 * the CPU: previews, visibility, files).  The host uses it only for plugins
 * loaded into its own process.
 *
 * Context.  The host calls render_gl on a thread where it has made current
 * an OpenGL 3.3 (or later) core-profile context that it keeps for this
 * instance's rendering: the same context at every call, its state (bound
 * objects, program, viewport, enables) the plugin's to change and keep.
 * The context shares objects (textures) with the one that shows the
 * frames.  Before destroying the instance, the host calls release_gl with
 * that context current, and the plugin deletes the GL objects it made in
 * it; an instance destroyed without release_gl leaks them, never touches
 * GL from its destroy.
 *
 * Target.  `texture` names a GL_TEXTURE_2D of frame_width x frame_height
 * texels, internal format GL_RGBA8, GL_RGBA16F or GL_RGBA32F, made by the
 * host.  Texel (x, y) is frame pixel (x, y), row 0 the top row as in
 * arbor_image, holding what *out of arbor.renderer/2 would (straight colour,
 * the background composited).  A call writes the request's region of it by
 * the pass's rule (SUPERSAMPLE blends into what the texture holds) and
 * leaves the other texels.  It returns once the GL commands are issued; the
 * host finishes or fences before another context reads the texture.  No
 * depth and no visibility are produced.  Cancellation: each texel of the
 * region holds its contents before the call or its final value.
 * ------------------------------------------------------------------------ */
#define ARBOR_INTERFACE_RENDERER_GL "arbor.renderer-gl/1"

typedef struct arbor_gl_target {
    uint32_t struct_size;
    uint32_t texture;      /* a GLuint of the current context's share group */
    uint32_t width;        /* the texture's size: the request's frame */
    uint32_t height;
} arbor_gl_target;
#define ARBOR_MIN_SIZE_arbor_gl_target ARBOR_SIZE_THROUGH(arbor_gl_target, height) /* through ABI 1.5 */

typedef struct arbor_renderer_gl_v1 {
    uint32_t struct_size;
    uint32_t reserved0;
    /* Render `request->pass` of the request's region into the target.
     * [instance] [borrowed: request and target until return] */
    arbor_status (*render_gl)(arbor_plugin *plugin, const arbor_render_request_v2 *request,
                              const arbor_gl_target *target, arbor_task *task);
    /* Delete the GL objects made in the host's context (current now);
     * render_gl may be called again afterwards and makes them anew.
     * [instance] */
    arbor_status (*release_gl)(arbor_plugin *plugin);
} arbor_renderer_gl_v1;
#define ARBOR_MIN_SIZE_arbor_renderer_gl_v1 ARBOR_SIZE_THROUGH(arbor_renderer_gl_v1, release_gl) /* through ABI 1.5 */

#endif /* ARBOR_RENDERER_H */
