/*
 * arbor/image.h - an RGBA float image the host allocates and a plugin fills
 * (renderings, legends).
 *
 * Colours are display-encoded sRGB values in [0, 1] with premultiplied alpha,
 * the space transfer functions are written in and composited in.  Row 0 is the
 * top of the image.
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
} arbor_image;

#endif /* ARBOR_IMAGE_H */
