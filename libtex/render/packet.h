/* packet.h - a packet's lookups ahead, in rows and lanes (libtex internal)
 *
 * render.c traces a tile's eye rays first; their hits' textures are looked up together
 * (packet.c): each primitive in batched calls over many points, a map's footprints and
 * trilinear lookups in vector lanes where the CPU has AVX-512 (x86/packet_x86.c).
 */
#ifndef TEX_PACKET_H
#define TEX_PACKET_H

#include "appfn.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Points per batch, a multiple of 8: a packet's hits.  At 256 the batch's rows (struct frames),
 * 2 KiB apart, shared few L1 sets, and every scene took 1-4 % longer. */
enum { CHUNK = 64 };

/* The points of a batch in lanes: the shading frames (D, N, width: rows of its own, or a
 * lanes' queue's, which are not copied) and the mappings' gradients gu, gv and placement
 * scales su, sv of those whose footprints go in lanes. */
struct frames {
    const double *d[3], *nn[3], *w;
    double rows[7][CHUNK]; /* D, N and width where the batch makes them (batch_widths) */
    double gu[3][CHUNK], gv[3][CHUNK], su[CHUNK], sv[CHUNK];
    double gw[3][CHUNK]; /* band-limited solids: the gradient of w */
    /* for bumps: the unit tangents e1, e2 and the placed u's and v's derivatives along them
     * (du1, dv1, du2, dv2), as footprint_unit and placed_derivatives make them */
    double e1[3][CHUNK], e2[3][CHUNK], du[2][CHUNK], dv[2][CHUNK];
    int shared; /* gu, gv, gw, su, sv hold lane 0's only, which every lane shares */
};

#ifdef __cplusplus
}
#endif
#endif
