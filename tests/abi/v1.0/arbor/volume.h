/*
 * arbor/volume.h - a scalar volume on a regular grid, as importers produce it
 * and every later stage reads it.
 *
 * Geometry follows DICOM patient coordinates (LPS: +x to the patient's left,
 * +y posterior, +z superior), in millimetres.  The centre of voxel (i, j, k) is
 *
 *     p = origin + D * (spacing[0]*i, spacing[1]*j, spacing[2]*k)
 *
 * where D is the 3x3 matrix of direction cosines stored row-major in
 * `direction` (column c is the unit LPS vector of grid axis c).  The identity
 * means the grid axes run along L, P and S.  Files in other conventions (NIfTI
 * RAS, VTK's unoriented data) are converted by their importer.
 *
 * Stored values map to physical ones by physical = stored * value_scale +
 * value_offset (CT: stored 0 with offset -1024 is -1024 HU).  The contour tree
 * is computed on stored values; a positive scale leaves it unchanged.
 *
 * The voxel with grid index (i, j, k) is at byte offset
 * i*strides[0] + j*strides[1] + k*strides[2] from `voxels`.  Volumes the host
 * allocates are contiguous with i fastest: strides = { s, s*nx, s*nx*ny } for
 * s = arbor_voxel_size(voxel_type); the voxel index is then i + nx*(j + ny*k).
 */
#ifndef ARBOR_VOLUME_H
#define ARBOR_VOLUME_H

#include "abi.h"

typedef uint32_t arbor_voxel_type;
#define ARBOR_VOXEL_UNKNOWN 0u
#define ARBOR_VOXEL_U8 1u
#define ARBOR_VOXEL_I8 2u
#define ARBOR_VOXEL_U16 3u
#define ARBOR_VOXEL_I16 4u
#define ARBOR_VOXEL_U32 5u
#define ARBOR_VOXEL_I32 6u
#define ARBOR_VOXEL_F32 7u
#define ARBOR_VOXEL_F64 8u

/* Bytes per voxel, 0 for an unknown type. */
static inline uint32_t arbor_voxel_size(arbor_voxel_type type)
{
    switch (type) {
    case ARBOR_VOXEL_U8:
    case ARBOR_VOXEL_I8: return 1;
    case ARBOR_VOXEL_U16:
    case ARBOR_VOXEL_I16: return 2;
    case ARBOR_VOXEL_U32:
    case ARBOR_VOXEL_I32:
    case ARBOR_VOXEL_F32: return 4;
    case ARBOR_VOXEL_F64: return 8;
    default: return 0;
    }
}

/* Short stable name ("u8", "i16", "f32"...), or "unknown". */
static inline const char *arbor_voxel_type_name(arbor_voxel_type type)
{
    switch (type) {
    case ARBOR_VOXEL_U8: return "u8";
    case ARBOR_VOXEL_I8: return "i8";
    case ARBOR_VOXEL_U16: return "u16";
    case ARBOR_VOXEL_I16: return "i16";
    case ARBOR_VOXEL_U32: return "u32";
    case ARBOR_VOXEL_I32: return "i32";
    case ARBOR_VOXEL_F32: return "f32";
    case ARBOR_VOXEL_F64: return "f64";
    default: return "unknown";
    }
}

typedef struct arbor_volume {
    uint32_t struct_size;
    arbor_voxel_type voxel_type;
    int64_t dims[3];     /* voxels along i, j, k; each > 0 */
    int64_t strides[3];  /* bytes between neighbours along i, j, k */
    double spacing[3];   /* mm between voxel centres along i, j, k; each > 0 */
    double origin[3];    /* LPS mm of the centre of voxel (0, 0, 0) */
    double direction[9]; /* row-major 3x3 direction cosines, see above */
    double value_scale;  /* physical = stored * value_scale + value_offset */
    double value_offset;
    const char *value_unit; /* unit of physical values: "HU", "" if unknown */
    /* Voxel (0, 0, 0).  Read-only when the volume is an input of a call. */
    void *voxels;
} arbor_volume;

#endif /* ARBOR_VOLUME_H */
