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
 * Order and instances.  To choose an importer the host creates an instance of
 * every importer, calls probe once and destroys it; the instance that reads is
 * another one.  Reading is read_header, then, when the host accepts the
 * header, read_voxels on the same instance and path, with no call between
 * them; a refused header gets no read_voxels.  An instance may read several
 * files over its life (the workstation opens one after another).  All calls
 * are [instance].
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
     * the dot: ".nrrd;.nhdr".  "/" means the importer reads folders.  Static;
     * the host breaks ties between equal confidences by it. */
    const char *suffixes;

    /* Confidence in [0, 100] that this importer reads `path`: 0 cannot, 100
     * recognised by content (magic bytes).  `head` holds the first head_size
     * bytes of the file, at most 4096 (head_size is 0 for folders and empty
     * files, and head may then be NULL).  Must be cheap: it is called for
     * every importer on every open that names no importer.  A path you do not
     * read is confidence 0 with ARBOR_OK, not an error.
     * [instance] [cheap] [borrowed: path and head until return] */
    arbor_status (*probe)(arbor_plugin *plugin, const char *path, const uint8_t *head,
                          uint64_t head_size, int32_t *confidence);

    /* Parse the header of `path` and fill every field of *out except strides
     * and voxels (out->struct_size is set by the host, every other field is
     * zero).  Strings written into *out stay valid until the next call into
     * the instance (the host copies them); value_unit NULL means "".  Read no
     * voxels and allocate nothing in proportion to the sizes the file claims.
     * [instance] [borrowed: path until return] */
    arbor_status (*read_header)(arbor_plugin *plugin, const char *path, arbor_task *task,
                                arbor_volume *out);

    /* Fill volume->voxels.  The host set dims, voxel_type and geometry to what
     * read_header returned and allocated voxels with volume->strides (i
     * fastest, contiguous).  The memory is not zero-filled: write every
     * voxel.  Report progress; honour cancellation.  [instance]
     * [borrowed: path until return] [host-owned: volume->voxels] */
    arbor_status (*read_voxels)(arbor_plugin *plugin, const char *path, arbor_task *task,
                                arbor_volume *volume);
} arbor_importer_v1;

#endif /* ARBOR_IMPORTER_H */
