/*
 * arbor/image.h - an RGBA float image the host allocates and a plugin fills
 * (renderings, legends).
 *
 * Colours are display-encoded sRGB values in [0, 1] with premultiplied alpha,
 * the space transfer functions are written in and composited in.  Row 0 is the
 * top of the image.  The pixels are [host-owned]: write them during the call
 * only.
 */
#ifndef ARBOR_IMAGE_H
#define ARBOR_IMAGE_H

#include "abi.h"

typedef struct arbor_image {
    uint32_t struct_size;
    uint32_t width;  /* > 0 */
    uint32_t height; /* > 0 */
    uint32_t reserved0;
    int64_t row_stride; /* floats between the starts of two rows of rgba, >= 4 * width */
    float *rgba;        /* pixel (x, y) at rgba[y * row_stride + 4 * x] */
    /* [width * height] or NULL when not wanted: distance in mm from the camera
     * to where the accumulated opacity first reaches 0.5, +infinity if never. */
    float *depth;
    /* Since ABI 1.1: check ARBOR_HAS_FIELD(arbor_image, struct_size,
     * label_visibility_count) before using these two.
     * [label_visibility_count] or NULL when not wanted: per label (the index
     * of its transfer function), its visibility: the sum over the image's
     * rays of the opacity its samples contributed, T * alpha, where T is the
     * transparency in front of the sample (Correa and Ma's visibility
     * histograms).  A label's share of the sum is what its structure
     * contributes to the picture.  The host fills the array with NaN; a
     * renderer that measures visibility writes every entry, one that cannot
     * leaves it as it is. */
    double *label_visibility;
    uint32_t label_visibility_count;
    uint32_t reserved1;
    /* Since ABI 1.2 (check ARBOR_HAS_FIELD(arbor_image, struct_size,
     * depth_stride)): floats between the starts of two rows of depth,
     * >= width; 0 (or an older host) means width.  With row_stride it lets
     * the host point rgba and depth at a tile inside a larger frame. */
    int64_t depth_stride;
} arbor_image;
#define ARBOR_MIN_SIZE_arbor_image ARBOR_SIZE_THROUGH(arbor_image, depth) /* through ABI 1.0 */

#endif /* ARBOR_IMAGE_H */
