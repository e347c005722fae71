/* noise.h - the thesis's gradient noise (Perlin 1985, thesis 5.2.2.1)
 *
 * n unit gradients G uniformly on the sphere and a random permutation F of
 * 0..n-1 are drawn from the seed.  The lattice point (i,j,k) gets
 *     G(i,j,k) = G[F[(i + F[(j + F[k mod n]) mod n]) mod n]]
 * and the noise at P is the sum over the 8 corners of P's cell of
 *     w(u) w(v) w(w) (G . (u,v,w)),   (u,v,w) = P - corner,
 *     w(t) = 2|t|^3 - 3|t|^2 + 1     (eqs. 5.1-5.3).
 * The sum is signed and lies in [-1,1] (in practice within about +-0.9);
 * it is 0 at every lattice point.
 *
 *   tex_noise_table t;
 *   tex_noise_init(&t, seed, 256, 0);       // n = 256, not periodic
 *   double s = tex_noise3(&t, x, y, z);      // signed
 *
 * With period p > 0 the lattice wraps every p cells along x and y, so a
 * field sampled over [0,p) tiles.
 */
#ifndef TEX_NOISE_H
#define TEX_NOISE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TEX_NOISE_MAX_GRADIENTS 4096

typedef struct tex_noise_table {
    int n;      /* gradients */
    int period; /* 0: none */
    int *perm;  /* F, n entries */
    float (*grad)[3];
} tex_noise_table;

int tex_noise_init(tex_noise_table *t, uint64_t seed, int n, int period);
void tex_noise_free(tex_noise_table *t);
double tex_noise3(const tex_noise_table *t, double x, double y, double z);

#ifdef __cplusplus
}
#endif
#endif
