/* stats_x86.h - map.c's statistics of a row in four lanes at once (AVX2)
 *
 * Called by map.c's row_take where tex_simd_level() allows: the same lanes (lane l takes the
 * samples x with x % 4 == l) and the same doubles, operation for operation, as its scalar
 * lane_take, so the figures do not depend on the SIMD level.
 */
#ifndef TEX_STATS_X86_H
#define TEX_STATS_X86_H

#include <stddef.h>

/* Four lanes' figures, each field an array a lane an element. */
struct tex_stats_lanes {
    double sum[4], s1[4], s2[4];
    float lo[4], hi[4];
    long long n[4], nan[4];
};

/* The first w - w % 4 samples of a row, nc floats apart, into L (only lo, hi and n when
 * !sums); k0 the shift. Returns w - w % 4. */
size_t tex_stats_row_avx2(struct tex_stats_lanes *L, const float *px, size_t w, int nc, double k0,
                          int sums);
/* The first w - w % 4 pixels of a row of three channels into L[0..2], channel c's shift
 * k0[c], with sums: each vector holds four consecutive samples (channel i % 3 of pixel
 * i / 3 of four pixels), each into its channel's lane.  Returns w - w % 4. */
size_t tex_stats_pixels3_avx2(struct tex_stats_lanes L[3], const float *px, size_t w,
                              const double k0[3]);

#endif
