/* rng.h - deterministic random numbers for primitives
 *
 * Every random choice in libtex comes from here, never from libc rand(),
 * so that a seed gives the same map on every machine, thread count and
 * SIMD level.
 *
 *   tex_rng r; tex_rng_seed(&r, seed);
 *   double x = tex_rng_uniform(&r);        // [0,1)
 *   uint32_t k = tex_rng_below(&r, n);     // 0..n-1, unbiased
 *   uint64_t h = tex_hash64(x ^ tex_hash64(y)); // stateless hashing
 *
 * The generator is xoshiro256** seeded through splitmix64.
 */
#ifndef TEX_RNG_H
#define TEX_RNG_H

#include "api.h"

#include <stdint.h>

TEX_API_BEGIN

typedef struct tex_rng {
    uint64_t s[4];
} tex_rng;

/* splitmix64's finaliser: a good 64-bit mixing function. */
static inline uint64_t tex_hash64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

void tex_rng_seed(tex_rng *r, uint64_t seed);

static inline uint64_t tex_rng_rotl(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

/* The next draw and the next in [0,1) with 53 bits: inline, as the renderer draws two for
 * every sample of every pixel (a call each was 2 % of a 9-spp render's instructions) */
static inline uint64_t tex_rng_next(tex_rng *r)
{
    uint64_t *s = r->s, result = tex_rng_rotl(s[1] * 5, 7) * 9, t = s[1] << 17;

    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = tex_rng_rotl(s[3], 45);
    return result;
}

static inline double tex_rng_uniform(tex_rng *r)
{
    return (tex_rng_next(r) >> 11) * 0x1.0p-53;
}

uint32_t tex_rng_below(tex_rng *r, uint32_t n); /* 0..n-1 */
double tex_rng_gauss(tex_rng *r);     /* standard normal */
void tex_rng_shuffle(tex_rng *r, int *a, int n); /* Fisher-Yates */

TEX_API_END
#endif
