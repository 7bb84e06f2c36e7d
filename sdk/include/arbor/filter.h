/*
 * arbor/filter.h - plugins that turn a volume into another volume on the same
 * grid (denoising, windowing) before the contour tree is built.
 */
#ifndef ARBOR_FILTER_H
#define ARBOR_FILTER_H

#include "host.h"
#include "plugin.h"
#include "volume.h"

#define ARBOR_INTERFACE_FILTER "arbor.filter/1"

typedef struct arbor_filter_v1 {
    /* Voxel type the output will have for this input (most filters keep the
     * input's).  ARBOR_ERROR_UNSUPPORTED for input types the filter rejects.
     * The host calls it right before apply, on the same thread and with the
     * same input and parameters.  [instance] [cheap]
     * [borrowed: input until return] */
    arbor_status (*output_type)(arbor_plugin *plugin, const arbor_volume *input,
                                arbor_voxel_type *out_type);

    /* Filter `input` into `output`.  The host allocated output with the
     * input's dims, geometry and value mapping, the voxel type output_type
     * returned, and contiguous strides.  The two never alias.  Parameters
     * were set before the call.  The output is not zero-filled: write every
     * voxel.  Address the input through its strides.  Filters of a chain run
     * one after another, each on the previous one's output.  [instance]
     * [borrowed: input until return] [host-owned: output->voxels] */
    arbor_status (*apply)(arbor_plugin *plugin, const arbor_volume *input, arbor_volume *output,
                          arbor_task *task);
} arbor_filter_v1;

#endif /* ARBOR_FILTER_H */
