/* render_light.c - lights (the Iluminação lecture chapter, 7.2) and shadows
 *
 *   distant  parallel light from direction dir, no attenuation
 *   point    at pos; fatt = 1, 1/d^2, or min(1/(c1 + c2 d + c3 d^2), 1)
 *   spot     a point light times cos^c of the angle to its axis, 0 outside
 *            the cone
 *   area     a parallelogram pos + a edge1 + b edge2 sampled on an n x n
 *            jittered grid: soft shadows (each sample carries 1/n^2)
 */
#include <math.h>
#include <stdint.h>

#include "render/scene.h"

int tex_light_samples(const struct tex_light *l)
{
    return l->kind == TEX_LIGHT_AREA ? l->samples * l->samples : 1;
}

int tex_light_sample(const struct tex_light *l, int k, double jx, double jy, tex_v3 P, tex_v3 *L,
                     double *dist, double *fatt)
{
    tex_v3 pos = l->pos;
    if (l->kind == TEX_LIGHT_DISTANT) {
        *L = l->dir;
        *dist = INFINITY;
        *fatt = 1;
        return 1;
    }
    /* n a power of two 2^e (the usual 2, 4, 8): a mask, a shift and products by 2^-e
     * where divisions by n and n^2 stood, the same numbers (a product by a power of two
     * is exact as the quotient is, both rounded once), without the divisions' latency
     * on the way to the light's direction (a quarter of an area-lit render) */
    int n = l->samples, e = n > 0 && !(n & (n - 1)) ? __builtin_ctz((unsigned)n) : -1;
    union {
        uint64_t u;
        double d;
    } inv = {(uint64_t)(1023 - (e > 0 ? e : 0)) << 52}; /* 2^-e */
    if (l->kind == TEX_LIGHT_AREA) {
        double a, b;
        if (e >= 0)
            a = ((k & (n - 1)) + jx) * inv.d, b = ((k >> e) + jy) * inv.d;
        else
            a = ((k % n) + jx) / n, b = ((k / n) + jy) / n;
        pos = tex_v3_add(pos, tex_v3_add(tex_v3_scale(l->edge1, a), tex_v3_scale(l->edge2, b)));
    }
    double f;
    if (!tex_light_point_at(l, &pos, &P, L, dist, &f))
        return 0;
    if (l->kind == TEX_LIGHT_AREA) {
        if (e >= 0)
            f *= inv.d * inv.d;
        else
            f /= tex_light_samples(l);
    }
    *fatt = f;
    return f > 0;
}

/* ---- the environment ----------------------------------------------------------- */

void tex_environment_eval(const struct tex_environment *e, const tex_v3 *d, double spread,
                          float rgb[3])
{
    tex_v3 m = tex_xform_dir(&e->to_map, *d);
    double y = m.y > 1 ? 1 : m.y < -1 ? -1 : m.y;
    double u = 0.5 + atan2(m.x, m.z) / (2 * M_PI), v = acos(y) / M_PI;
    /* the footprint: spread radians are spread / pi of the map's height */
    tex_texture_eval(e->map, u, v, 0, spread > 0 ? spread / M_PI : 0, rgb);
    for (int k = 0; k < 3; k++)
        rgb[k] = (float)(rgb[k] * e->intensity);
}
