/* rng.c - xoshiro256** seeded by splitmix64 */
#include <math.h>

#include "base/rng.h"

void tex_rng_seed(tex_rng *r, uint64_t seed)
{
    for (int i = 0; i < 4; i++)
        r->s[i] = seed = tex_hash64(seed);
}

uint32_t tex_rng_below(tex_rng *r, uint32_t n)
{
    /* Lemire's multiply-and-reject: unbiased without a division per call. */
    uint64_t m = (uint64_t)(uint32_t)(tex_rng_next(r) >> 32) * n;
    uint32_t lo = (uint32_t)m;

    if (lo < n) {
        uint32_t t = -n % n;
        while (lo < t) {
            m = (uint64_t)(uint32_t)(tex_rng_next(r) >> 32) * n;
            lo = (uint32_t)m;
        }
    }
    return m >> 32;
}

double tex_rng_gauss(tex_rng *r)
{
    /* Box-Muller; the spare value is dropped to keep the state simple. */
    double u1 = 1.0 - tex_rng_uniform(r), u2 = tex_rng_uniform(r);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

void tex_rng_shuffle(tex_rng *r, int *a, int n)
{
    for (int i = n - 1; i > 0; i--) {
        int j = tex_rng_below(r, (uint32_t)i + 1), t = a[i];
        a[i] = a[j];
        a[j] = t;
    }
}
