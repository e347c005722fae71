/* test_sample - the sampler's lookup (tex_sample): every SIMD level gives the portable
 * path's floats, to the bit */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "base/simd.h"
#include "ops/transform.h"
#include "unit.h"

static uint64_t state = 7;

/* a double in [lo, hi) */
static double rnd(double lo, double hi)
{
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(state >> 11) / 9007199254740992.0;
}

/* Lookups of maps of 1 to 4 channels, odd sides, through each edge rule, a band of rows
 * among them: points inside, across the edges, far outside, huge and NaN; footprints from
 * none to past 32 pixels (one tap to the most), the warp's two taps among them; the
 * results of each level against the portable path's. */
static void levels_agree(void)
{
    static const enum tex_edge edges[] = {TEX_EDGE_CLAMP, TEX_EDGE_WRAP, TEX_EDGE_MIRROR,
                                          TEX_EDGE_BACKGROUND};
    static const float bg[4] = {0.25f, 0.5f, 0.75f, 0.5f};
    int best = tex_simd_level(), cases = 0, taps2 = 0;

    for (int nc = 1; nc <= 4; nc++) {
        tex_map *m = tex_map_new(37 + nc, 23, nc);
        if (!m)
            return;
        for (size_t i = 0; i < (size_t)m->w * m->h * nc; i++)
            m->px[i] = (float)rnd(-1, 2);
        m->px[3] = -0.0f;
        for (int level = best; level > TEX_SIMD_SCALAR; level--) {
            int same = 1;
            for (size_t e = 0; e < sizeof edges / sizeof *edges; e++)
                for (int band = 0; band < 2; band++)
                    for (int k = 0; k < 4000; k++, cases++) {
                        struct tex_sampler s;
                        double x = rnd(-20, m->w + 20), y = rnd(-20, m->h + 20), du[2], dv[2];
                        float want[4], got[4];
                        double reach = k % 4 == 0 ? 0.9 : k % 4 == 1 ? 2 : k % 4 == 2 ? 8 : 80;
                        du[0] = rnd(-reach, reach), du[1] = rnd(-reach, reach);
                        dv[0] = rnd(-reach, reach), dv[1] = rnd(-reach, reach);
                        if (k % 7 == 0) /* the warp's usual: about one pixel, two taps */
                            du[0] = 1 + rnd(0, 0.5), du[1] = 0, dv[0] = rnd(-0.5, 0.5), dv[1] = 1;
                        if (k % 97 == 0)
                            x = k % 2 ? NAN : 1e300;
                        if (k % 89 == 0)
                            x = floor(x) + 0.5, y = floor(y) + 0.5, du[0] = du[1] = 0;
                        tex_sampler_init(&s, m, edges[e], bg);
                        if (band) /* m as rows 5.. of a map 40 rows tall */
                            s.row0 = 5, s.rows = 40;
                        s.level = TEX_SIMD_SCALAR;
                        tex_sample(&s, x, y, du, dv, want);
                        s.level = level;
                        tex_sample(&s, x, y, du, dv, got);
                        same &= !memcmp(want, got, nc * sizeof *got);
                        taps2 += fabs(du[0]) + fabs(du[1]) > 1 && fabs(du[0]) < 1.5;
                    }
            CHECKF(same, "%d channels, level %d: the portable path's floats", nc, level);
        }
        tex_map_free(m);
    }
    if (best == TEX_SIMD_SCALAR)
        printf("ok - # this CPU has no AVX2: one path to compare\n");
    else
        CHECKF(cases > 100000 && taps2 > 1000, "%d lookups compared, %d of two taps along u",
               cases, taps2);
}

/* A lookup of one tap at a pixel's centre is that pixel, on every level */
static void centres(void)
{
    tex_map *m = tex_map_new(9, 7, 3);
    int ok = 1;
    if (!m)
        return;
    for (int i = 0; i < 9 * 7 * 3; i++)
        m->px[i] = (float)rnd(0, 1);
    for (int level = tex_simd_level(); level >= TEX_SIMD_SCALAR; level--)
        for (int y = 0; y < 7; y++)
            for (int x = 0; x < 9; x++) {
                struct tex_sampler s;
                const double du[2] = {1, 0}, dv[2] = {0, 1};
                float v[4];
                tex_sampler_init(&s, m, TEX_EDGE_WRAP, NULL);
                s.level = level;
                tex_sample(&s, x + 0.5, y + 0.5, du, dv, v);
                ok &= !memcmp(v, tex_map_px(m, x, y), 3 * sizeof *v);
            }
    CHECK(ok, "one tap at a pixel's centre gives the pixel, on every level");
    tex_map_free(m);
}

/* tex_affine_rows's whole-pixel translation copies rows in runs: the pixels the sampler's
 * nearest lookup gives, through every edge rule, from a band of rows among the map's, with
 * shifts inside, across and far beyond the sides, and a channel added by the background. */
static void translation_copies(void)
{
    static const float bg[4] = {0.25f, 0.5f, 0.75f, 0.5f};
    tex_map *m = tex_map_new(13, 5, 3);
    int ok = 1, cases = 0;
    if (!m)
        return;
    for (int i = 0; i < 13 * 5 * 3; i++)
        m->px[i] = (float)rnd(0, 1);
    for (int e = TEX_EDGE_CLAMP; e <= TEX_EDGE_BACKGROUND; e++)
        for (int nc = 3; nc <= 4; nc++)
            for (int t = 0; t < 40; t++) {
                double a[6] = {1, 0, floor(rnd(-40, 40)), 0, 1, floor(rnd(-12, 12))};
                int w = 1 + (int)rnd(0, 30), h = 1 + (int)rnd(0, 9), y0 = (int)rnd(-3, 6);
                tex_map *r = tex_map_new(w, h, nc), *src = tex_map_channels(m, nc);
                struct tex_sampler s;
                const double du[2] = {1, 0}, dv[2] = {0, 1};
                if (!r || !src || tex_affine_rows(m, 2, 11, r, y0, a, e, bg) < 0) {
                    ok = 0;
                } else {
                    /* the map as rows 2..6 of one 11 rows tall, looked up pixel by pixel */
                    tex_sampler_init(&s, src, e, bg);
                    s.row0 = 2, s.rows = 11, s.nearest = 1;
                    for (int y = 0; y < h; y++)
                        for (int x = 0; x < w; x++) {
                            float v[4];
                            tex_sample(&s, x + 0.5 + a[2], y0 + y + 0.5 + a[5], du, dv, v);
                            ok &= !memcmp(v, tex_map_px(r, x, y), nc * sizeof *v);
                        }
                }
                cases++;
                tex_map_free(r);
                tex_map_free(src);
            }
    CHECKF(ok, "a whole-pixel translation gives the nearest lookup's pixels (%d cases)", cases);
    tex_map_free(m);
}

int main(void)
{
    levels_agree();
    centres();
    translation_copies();
    return unit_done();
}
