/*
 * arbor/importer.h - plugins that read a volume from a file or a folder.
 *
 * Reading happens in two calls so that the host, not each plugin, decides
 * whether a volume is too large before any voxel memory exists:
 *
 *   probe        how confident the importer is that it reads this path;
 *   read_header  dims, voxel type, geometry and value mapping;
 *   read_voxels  fill a buffer the host allocated from that header.
 *
 * The host validates the header (positive dims, no overflow, known type, its
 * memory limit) between the two calls.  An instance may keep what it parsed in
 * read_header for the read_voxels call that follows on the same path.
 *
 * Parameters (params.h) carry what a file cannot say, e.g. the dims of a
 * headerless raw file or the series to pick from a DICOM folder.
 */
#ifndef ARBOR_IMPORTER_H
#define ARBOR_IMPORTER_H

#include "host.h"
#include "plugin.h"
#include "volume.h"

#define ARBOR_INTERFACE_IMPORTER "arbor.importer/1"

typedef struct arbor_importer_v1 {
    /* File name suffixes this importer reads, lowercase, ';'-separated, with
     * the dot: ".nrrd;.nhdr".  "/" means the importer reads folders. */
    const char *suffixes;

    /* Confidence in [0, 100] that this importer reads `path`: 0 cannot, 100
     * recognised by content (magic bytes).  `head` holds the first head_size
     * bytes of the file (head_size may be 0 for folders or short files).
     * Must be cheap: it is called for every importer on every open. */
    arbor_status (*probe)(arbor_plugin *plugin, const char *path, const uint8_t *head,
                          uint64_t head_size, int32_t *confidence);

    /* Parse the header of `path` and fill every field of *out except strides
     * and voxels (out->struct_size is set by the host).  Strings written into
     * *out stay valid until the next call into the instance. */
    arbor_status (*read_header)(arbor_plugin *plugin, const char *path, arbor_task *task,
                                arbor_volume *out);

    /* Fill volume->voxels.  The host set dims, voxel_type and geometry to what
     * read_header returned and allocated voxels with volume->strides (i
     * fastest, contiguous).  Report progress; honour cancellation. */
    arbor_status (*read_voxels)(arbor_plugin *plugin, const char *path, arbor_task *task,
                                arbor_volume *volume);
} arbor_importer_v1;

#endif /* ARBOR_IMPORTER_H */
