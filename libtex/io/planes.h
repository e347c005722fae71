/* planes.h - a scanline's samples as OpenEXR stores them, each channel's run after another,
 * and a map's pixels, each channel's sample beside the others, moved from one to the other
 *
 * The stream's reader and writer (stream.c) hand these to OpenEXR's core library as its
 * unpack and pack routines for float channels, where its own go a sample at a time.
 * plane[k] is the run of the samples that are channel k of the pixels (k < nc, 1..4).  Only
 * moves: the floats are the same at every SIMD level (three and four channels are moved eight
 * pixels at a time with AVX2).
 *
 *   const float *plane[3] = {r, g, b};
 *   tex_planes_join(px, plane, 3, w);   // px: r0 g0 b0 r1 g1 b1 ...
 */
#ifndef TEX_PLANES_H
#define TEX_PLANES_H

#include <stddef.h>

/* px[x nc + k] = plane[k][x] for x < w */
void tex_planes_join(float *px, const float *const *plane, int nc, size_t w);
/* plane[k][x] = px[x nc + k] for x < w */
void tex_planes_split(float *const *plane, const float *px, int nc, size_t w);

#endif
