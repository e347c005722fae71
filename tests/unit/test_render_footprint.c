/* test_render_footprint.c - texture footprints after curved mirrors and lenses
 *
 * A checkered floor seen in a convex mirror ball: near the ball's rim the
 * reflection squeezes many checks into a pixel.  One filtered sample per
 * pixel must come close to a 64-sample reference there (the footprint grew
 * with the mirror's curvature), much closer than one unfiltered sample,
 * which aliases.  Through a glass ball the footprint must follow the lens:
 * neither blur the floor away nor, for a wall far behind, stay too sharp.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "error.h"
#include "render.h"
#include "fixtures.h"
#include "unit.h"

#define N 96

static tex_map *render(const char *extra, int spp, int filter)
{
    char sc[2048];
    snprintf(sc, sizeof sc,
             "image %d %d samples %d depth 3 filter %s ambient 1 1 1 background 0.5 0.5 0.5\n"
             "camera { eye 0 0.4 -4 look 0 0 0 fov 32 }\n"
             "texture checks checker { nu 2 nv 2 size 64 }\n"
             "surface floor { Ka 1 Kd 1 Ks 0 apply checks { repeat 4 4 Kd = f } }\n"
             "surface mirror { Ka 0 Kd 0 Ks 0 Kr 1 }\n"
             "surface glass { Ka 0 Kd 0 Ks 0 Kr 0 Kt 1 ior 1.5 }\n"
             "plane { distance -1 surface floor }\n%s",
             N, N, spp, filter ? "on" : "off", extra);
    return unit_render_text(sc, 0);
}

/* RMS difference from the reference over the ball's lower half (its
 * reflection of the floor), within rim..0.98 of the projected radius. */
static double rms(const tex_map *a, const tex_map *ref, double rim)
{
    double ppu = N / (2 * tan(16 * M_PI / 180)), d = sqrt(16 + 0.16);
    double rad = tan(asin(1 / d)) * ppu, cy = N / 2.0; /* the ball is centred */
    double s = 0;
    int n = 0;
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            double dx = x + 0.5 - N / 2.0, dy = y + 0.5 - cy, r = hypot(dx, dy);
            if (dy < 0 || r > 0.98 * rad || r < rim * rad)
                continue;
            double e = tex_map_px(a, x, y)[0] - tex_map_px(ref, x, y)[0];
            s += e * e, n++;
        }
    return n ? sqrt(s / n) : 1;
}

static void test_mirror(void)
{
    const char *ball = "sphere { radius 1 surface mirror }\n";
    tex_map *f = render(ball, 1, 1), *u = render(ball, 1, 0), *ref = render(ball, 64, 0);
    CHECK(f && u && ref, "mirror ball scenes render");
    if (f && u && ref) {
        double ef = rms(f, ref, 0.6), eu = rms(u, ref, 0.6);
        CHECKF(ef < 0.25 * eu && ef < 0.09,
               "checker in a convex mirror, near the rim: 1 filtered sample off the reference by "
               "%.4f RMS, 1 unfiltered by %.4f",
               ef, eu);
    }
    tex_map_free(f);
    tex_map_free(u);
    tex_map_free(ref);
}

/* Through a glass ball the floor is seen inverted: the lens terms must
 * neither alias nor blur it away (one filtered sample stays near the
 * reference). */
static void test_lens(void)
{
    const char *ball = "sphere { radius 1 surface glass }\n";
    tex_map *f = render(ball, 1, 1), *u = render(ball, 1, 0), *ref = render(ball, 64, 0);
    CHECK(f && u && ref, "glass ball scenes render");
    if (f && u && ref) {
        double ef = rms(f, ref, 0.6), eu = rms(u, ref, 0.6);
        CHECKF(ef < 0.05 && ef < 0.3 * eu,
               "checker through a glass ball: filtered %.4f RMS off the reference, unfiltered %.4f",
               ef, eu);
    }
    tex_map_free(f);
    tex_map_free(u);
    tex_map_free(ref);
}

/* A glass ball before a checkered wall 6 units behind it: the ball images a
 * wide stretch of the wall, inverted, into its disc.  Its beams cross a
 * focus just behind the ball and spread from there, so a pixel's footprint
 * on the wall is several times what the pixel angle alone gives: without
 * the lens term the filtered lookup is too sharp and aliases (0.13 RMS off
 * the reference against 0.06 with it). */
static void test_lens_wall(void)
{
    tex_map *img[3];
    for (int k = 0; k < 3; k++) {
        char sc[1024];
        snprintf(sc, sizeof sc,
                 "image %d %d samples %d depth 3 filter %s ambient 1 1 1 background 0.5 0.5 0.5\n"
                 "camera { eye 0 0 -4 look 0 0 0 fov 32 }\n"
                 "texture checks checker { nu 2 nv 2 size 64 }\n"
                 "surface wall { Ka 1 Kd 1 Ks 0 apply checks { scale 2 Kd = f } }\n"
                 "surface glass { Ka 0 Kd 0 Ks 0 Kr 0 Kt 1 ior 1.5 }\n"
                 "plane { normal 0 0 -1 distance -6 surface wall }\n"
                 "sphere { radius 1 surface glass }\n",
                 N, N, k == 2 ? 64 : 1, k == 0 ? "on" : "off");
        img[k] = unit_render_text(sc, 0);
    }
    CHECK(img[0] && img[1] && img[2], "glass ball before a wall: scenes render");
    if (img[0] && img[1] && img[2]) {
        /* the ball's whole disc, to 0.95 of its projected radius */
        double rad = tan(asin(0.25)) * N / (2 * tan(16 * M_PI / 180)), e[2] = {0, 0};
        int n = 0;
        for (int y = 0; y < N; y++)
            for (int x = 0; x < N; x++) {
                if (hypot(x + 0.5 - N / 2.0, y + 0.5 - N / 2.0) > 0.95 * rad)
                    continue;
                for (int k = 0; k < 2; k++) {
                    double d = tex_map_px(img[k], x, y)[0] - tex_map_px(img[2], x, y)[0];
                    e[k] += d * d;
                }
                n++;
            }
        e[0] = sqrt(e[0] / n), e[1] = sqrt(e[1] / n);
        CHECKF(e[0] < 0.09 && e[0] < 0.3 * e[1],
               "checker wall through a glass ball: filtered %.4f RMS off the reference, "
               "unfiltered %.4f",
               e[0], e[1]);
    }
    for (int k = 0; k < 3; k++)
        tex_map_free(img[k]);
}

int main(void)
{
    test_mirror();
    test_lens();
    test_lens_wall();
    return unit_done();
}
