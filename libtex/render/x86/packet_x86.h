/* packet_x86.h - a packet's footprints and mappings in AVX-512 lanes, its footprints and
 * a plane's mapping in AVX2's too (packet.c's twins)
 *
 * Each performs the scalar path's operations in its order (footprint.c, mapping.c), so
 * the same bytes.
 */
#ifndef TEX_PACKET_X86_H
#define TEX_PACKET_X86_H

#include "../../base/x86/simd_x86.h"
#include "../packet.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef TEX_X86
/* footprint_width2 of the n <= 8 affine points from i on into fw2[i...], and where bump,
 * the frames' bump members; returns the lanes seen head-on (bit k: lane i + k), which the
 * scalar path takes. */
TEX_AVX512 unsigned tex_footprints8_avx512(struct frames *fr, int i, int n, int bump, double *fw2);
/* The footprint widths of the n <= 8 band-limited solid points from i on, as
 * sqrt(tex_solid_width2) makes them under an affine mapping, into fw[i...]; returns the
 * lanes seen head-on. */
TEX_AVX512 unsigned tex_solid_footprints8_avx512(const struct frames *fr, int i, int n,
                                                 double *fw);
/* tex_footprints8_avx512 and tex_solid_footprints8_avx512 in AVX2's lanes: n <= 4 points */
TEX_AVX2 unsigned tex_footprints4_avx2(struct frames *fr, int i, int n, int bump, double *fw2);
TEX_AVX2 unsigned tex_solid_footprints4_avx2(const struct frames *fr, int i, int n, double *fw);
/* map_hit of a plane's planar mapping over the n <= 8 lanes of L's points from i on: the
 * mapping's u0, v0 and the placed u, v; returns the lanes inside the window. */
TEX_AVX512 unsigned tex_plane_map8_avx512(const struct tex_lanes *L, int i, int n, double *u0,
                                          double *v0, double *u, double *v);
/* tex_plane_map8_avx512 in AVX2's lanes: n <= 4 points */
TEX_AVX2 unsigned tex_plane_map4_avx2(const struct tex_lanes *L, int i, int n, double *u0,
                                      double *v0, double *u, double *v);
/* map_hit of a natural mapping on a box, cylinder, cone or sphere over the n <= 8 lanes of
 * L's points from i on, each lane's face into face[], and the mapping's gradients into fr's
 * rows; returns the lanes inside the window that have gradients. */
TEX_AVX512 unsigned tex_natural_map8_avx512(const struct tex_lanes *L, int i, int n, double *u0,
                                            double *v0, double *u, double *v, int *face,
                                            struct frames *fr);
#endif

#ifdef __cplusplus
}
#endif
#endif
