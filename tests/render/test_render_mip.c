/* test_render_mip.c - trilinear lookups in a texture map's mip-map pyramid
 *
 * tex_texture_eval blends the two pyramid levels around lod = log2(fw side)
 * with weight lod - floor(lod), the logarithm taken from the exponent bits and
 * a polynomial (render/mipmap.h).  A footprint that is a power of two of
 * texels looks up one level alone; between two of them the value must be the
 * blend of those two with libm's log2 as the weight, within 1e-5, for grey and
 * colour maps, square or not.  Coordinates wrap: the map repeats.  Many lookups at once
 * (tex_texture_points, in vector lanes where the CPU has AVX-512) give the portable path's
 * floats, whatever their number.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fixtures.h"
#include "render/scene.h"
#include "base/rng.h"
#include "base/simd.h"
#include "unit.h"

static struct tex_texture *texture(int w, int h, int nc, uint64_t seed)
{
    struct tex_texture *t = calloc(1, sizeof *t);
    t->mip = malloc(sizeof *t->mip);
    t->mip[0] = unit_random_map(w, h, nc, seed);
    if (!t->mip[0] || tex_texture_build_mip(t) < 0)
        printf("# mip: %s\n", tex_errmsg());
    return t;
}

static void texture_free(struct tex_texture *t)
{
    for (int l = 0; l < t->nlevels; l++)
        tex_map_free(t->mip[l]);
    free(t->mip);
    free(t);
}

/* The largest difference from the libm-weighted blend of the two levels' lookups. */
static double blend_error(const struct tex_texture *t, uint64_t seed)
{
    int side = t->mip[0]->w > t->mip[0]->h ? t->mip[0]->w : t->mip[0]->h;
    tex_rng r;
    tex_rng_seed(&r, seed);
    double worst = 0;
    for (int i = 0; i < 4000; i++) {
        double u = tex_rng_uniform(&r), v = tex_rng_uniform(&r);
        double lod = tex_rng_uniform(&r) * (t->nlevels + 1) - 1; /* magnified to clamped */
        double fw = exp2(lod) / side;
        float f[3], f0[3], f1[3];
        tex_texture_eval(t, u, v, 0, fw, f);
        double l = floor(log2(fw * side)), a = log2(fw * side) - l;
        tex_texture_eval(t, u, v, 0, exp2(l) / side, f0);
        tex_texture_eval(t, u, v, 0, exp2(l + 1) / side, f1);
        for (int c = 0; c < 3; c++) {
            double ref = lod > 0 ? f0[c] * (1 - a) + f1[c] * a : f0[c];
            worst = fmax(worst, fabs(f[c] - ref));
        }
    }
    return worst;
}

static void test_blend(void)
{
    static const int shapes[][3] = {{64, 64, 1}, {64, 16, 3}, {17, 40, 2}};
    for (int i = 0; i < 3; i++) {
        struct tex_texture *t = texture(shapes[i][0], shapes[i][1], shapes[i][2], 7 + i);
        double e = blend_error(t, 100 + i);
        CHECKF(e < 2e-5, "%dx%d map, %d channels: trilinear blend within 2e-5 of log2's (%.2g)",
               shapes[i][0], shapes[i][1], shapes[i][2], e);
        texture_free(t);
    }
}

static void test_wrap(void)
{
    struct tex_texture *t = texture(32, 32, 3, 3);
    int same = 1;
    for (int i = 0; i < 256; i++) {
        double u = (i * 37 % 256) / 256.0, v = (i * 91 % 256) / 256.0, fw = i / 2048.0;
        float a[3], b[3];
        tex_texture_eval(t, u, v, 0, fw, a);
        tex_texture_eval(t, u + 3, v - 2, 0, fw, b);
        same &= a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    }
    CHECK(same, "a map repeats: (u + 3, v - 2) looks up (u, v)");
    float a[3], b[3];
    tex_texture_eval(t, 0.3, 0.6, 0, INFINITY, a);
    tex_texture_eval(t, 0.9, 0.1, 0, 1e300, b);
    const float *top = t->mip[t->nlevels - 1]->px;
    CHECK(a[0] == top[0] && b[2] == top[2], "a footprint wider than the map: its mean");
    tex_texture_eval(t, NAN, 0.5, 0, 0, a);
    CHECK(a[0] == a[0], "a coordinate that is not a number looks up a texel, not NaN");
    texture_free(t);
}

/* n points of t through tex_texture_points at the SIMD level in use, at the portable level,
 * and one at a time: the same floats (values and gradients) all three ways */
static int points_agree(const struct tex_texture *t, int n, const double *u, const double *v,
                        const double *fw2)
{
    float *o = calloc(3 * n, sizeof *o), *o0 = calloc(3 * n, sizeof *o0), o1[3];
    double *g = calloc(2 * n, sizeof *g), *g0 = calloc(2 * n, sizeof *g0), g1[2];
    tex_texture_points(t, n, u, v, fw2, o, g);
    int best = tex_simd_level(), same = 1;
    tex_simd_limit(TEX_SIMD_SCALAR);
    tex_texture_points(t, n, u, v, fw2, o0, g0);
    tex_simd_limit(best);
    for (int i = 0; i < n; i++) {
        tex_texture_points(t, 1, u + i, v + i, fw2 + i, o1, g1);
        same &= !memcmp(o1, o + 3 * i, sizeof o1) && !memcmp(g1, g + 2 * i, sizeof g1);
    }
    same &= !memcmp(o, o0, 3 * n * sizeof *o) && !memcmp(g, g0, 2 * n * sizeof *g);
    free(o), free(o0), free(g), free(g0);
    return same;
}

static void test_points(void)
{
    /* the last two: 16 and 17 levels, more than the kernel keeps in registers */
    static const int shapes[][3] = {{64, 64, 1},  {37, 23, 3}, {1, 1, 1},     {5, 300, 4},
                                    {300, 2, 2},  {512, 96, 3}, {16, 16, 4},  {32768, 1, 1},
                                    {1, 40000, 3}};
    enum { N = 203 }; /* not a multiple of the lanes */
    double u[N], v[N], fw2[N];
    for (int s = 0; s < 9; s++) {
        struct tex_texture *t = texture(shapes[s][0], shapes[s][1], shapes[s][2], 40 + s);
        int side = shapes[s][0] > shapes[s][1] ? shapes[s][0] : shapes[s][1];
        tex_rng r;
        tex_rng_seed(&r, 90 + s);
        for (int i = 0; i < N; i++) {
            /* corners, texel centres, far repeats; footprints from none to wider than the
             * map, powers of two of texels, and not numbers */
            u[i] = i % 7 == 0 ? 0 : i % 7 == 1 ? 1e6 : tex_rng_uniform(&r) * (i % 3 ? 1 : 1e5);
            v[i] = i % 5 == 0 ? 0.5 / shapes[s][1] : tex_rng_uniform(&r) * (i % 2 ? 1 : 900);
            double x = exp2(tex_rng_uniform(&r) * 24 - 4) / side;
            fw2[i] = i % 11 == 0   ? 0
                     : i % 13 == 0 ? exp2(i % 9) / ((double)side * side)
                     : i % 17 == 0 ? (i % 2 ? NAN : INFINITY)
                                   : x * x;
        }
        CHECKF(points_agree(t, N, u, v, fw2),
               "%dx%d map, %d channels: %d lookups at once at %s give the portable path's "
               "floats and each point's alone",
               shapes[s][0], shapes[s][1], shapes[s][2], N, tex_simd_name(tex_simd_level()));
        texture_free(t);
    }
}

int main(void)
{
    test_blend();
    test_wrap();
    test_points();
    return unit_done();
}
