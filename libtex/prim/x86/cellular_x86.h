/* cellular_x86.h - the candidate lists' kernels for x86 (../cellular_impl.h)
 *
 * tex_cellular_lanes_avx2 is tex_cellular_lanes in 32-byte vectors, chosen at run
 * time (c->avx2); AVX2 alone brings no fused multiply-add, so each lane rounds as
 * the portable lanes do.  tex_cellular_roots_sse2 takes the lanes' square roots
 * two at a time (SSE2, x86-64's baseline): correctly rounded like sqrt(), without
 * its errno check.
 */
#ifndef TEX_CELLULAR_X86_H
#define TEX_CELLULAR_X86_H

void tex_cellular_lanes_avx2(const double *cx, const double *cy, const long *cid, long t0, long e,
                             const double *qx, const double *qy, int nv, int want_id,
                             int want_f2, int roots, double *a1, double *a2, long *i1);
/* a1[l] and (a2 not NULL) a2[l] = their square roots, l < n (even) */
void tex_cellular_roots_sse2(double *a1, double *a2, int n);

#endif
