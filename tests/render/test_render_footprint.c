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

#include "base/error.h"
#include "render/scene.h"
#include "fixtures.h"
#include "unit.h"

#define N 96

/* The floor (y = -1) and the wall (z = 6) are both declared; a scene's body
 * places the camera and the objects. */
static tex_map *render(const char *body, int spp, int filter)
{
    char sc[2048];
    snprintf(sc, sizeof sc,
             "image %d %d samples %d depth 3 filter %s ambient 1 1 1 background 0.5 0.5 0.5\n"
             "texture checks checker { nu 2 nv 2 size 64 }\n"
             "surface floor { Ka 1 Kd 1 Ks 0 apply checks { repeat 4 4 Kd = f } }\n"
             "surface wall { Ka 1 Kd 1 Ks 0 apply checks { scale 2 Kd = f } }\n"
             "surface mirror { Ka 0 Kd 0 Ks 0 Kr 1 }\n"
             "surface glass { Ka 0 Kd 0 Ks 0 Kr 0 Kt 1 ior 1.5 }\n%s",
             N, N, spp, filter ? "on" : "off", body);
    return unit_render_text(sc, 0);
}

/* Where to compare: the unit ball's disc, centred in the image, seen from
 * distance dist, between rim and rmax of its projected radius (lower: its
 * lower half only). */
struct region {
    double dist, rim, rmax;
    int lower;
};

/* RMS difference of one filtered (*ef) and one unfiltered (*eu) sample per
 * pixel from a 64-sample reference over the region; 0 if a scene failed. */
static int compare(const char *body, const struct region *rg, double *ef, double *eu)
{
    tex_map *img[3] = {render(body, 1, 1), render(body, 1, 0), render(body, 64, 0)};
    int ok = img[0] && img[1] && img[2];
    double rad = tan(asin(1 / rg->dist)) * N / (2 * tan(16 * M_PI / 180)), e[2] = {0, 0};
    int n = 0;
    for (int y = 0; ok && y < N; y++)
        for (int x = 0; x < N; x++) {
            double dx = x + 0.5 - N / 2.0, dy = y + 0.5 - N / 2.0, r = hypot(dx, dy);
            if ((rg->lower && dy < 0) || r > rg->rmax * rad || r < rg->rim * rad)
                continue;
            for (int k = 0; k < 2; k++) {
                double d = tex_map_px(img[k], x, y)[0] - tex_map_px(img[2], x, y)[0];
                e[k] += d * d;
            }
            n++;
        }
    *ef = n ? sqrt(e[0] / n) : 1;
    *eu = n ? sqrt(e[1] / n) : 1;
    for (int k = 0; k < 3; k++)
        tex_map_free(img[k]);
    return ok;
}

#define FLOOR_SCENE                                                                                \
    "camera { eye 0 0.4 -4 look 0 0 0 fov 32 }\nplane { distance -1 surface floor }\n"

/* the ball's lower half (its view of the floor), from 0.6 of its radius outwards;
 * the eye is sqrt(4^2 + 0.4^2) from its centre */
static const struct region floor_rim = {4.019950248448356, 0.6, 0.98, 1};

static void test_mirror(void)
{
    double ef, eu;
    int ok = compare(FLOOR_SCENE "sphere { radius 1 surface mirror }\n", &floor_rim, &ef, &eu);
    CHECK(ok, "mirror ball scenes render");
    if (ok)
        CHECKF(ef < 0.25 * eu && ef < 0.09,
               "checker in a convex mirror, near the rim: 1 filtered sample off the reference by "
               "%.4f RMS, 1 unfiltered by %.4f",
               ef, eu);
}

/* Through a glass ball the floor is seen inverted: the lens terms must
 * neither alias nor blur it away (one filtered sample stays near the
 * reference). */
static void test_lens(void)
{
    double ef, eu;
    int ok = compare(FLOOR_SCENE "sphere { radius 1 surface glass }\n", &floor_rim, &ef, &eu);
    CHECK(ok, "glass ball scenes render");
    if (ok)
        CHECKF(ef < 0.05 && ef < 0.3 * eu,
               "checker through a glass ball: filtered %.4f RMS off the reference, unfiltered %.4f",
               ef, eu);
}

/* A glass ball before a checkered wall 6 units behind it: the ball images a
 * wide stretch of the wall, inverted, into its disc.  Its beams cross a
 * focus just behind the ball and spread from there, so a pixel's footprint
 * on the wall is several times what the pixel angle alone gives: without
 * the lens term the filtered lookup is too sharp and aliases (0.13 RMS off
 * the reference against 0.06 with it). */
static void test_lens_wall(void)
{
    static const struct region disc = {4, 0, 0.95, 0}; /* the whole disc */
    double ef, eu;
    int ok = compare("camera { eye 0 0 -4 look 0 0 0 fov 32 }\n"
                     "plane { normal 0 0 -1 distance -6 surface wall }\n"
                     "sphere { radius 1 surface glass }\n",
                     &disc, &ef, &eu);
    CHECK(ok, "glass ball before a wall: scenes render");
    if (ok)
        CHECKF(ef < 0.09 && ef < 0.3 * eu,
               "checker wall through a glass ball: filtered %.4f RMS off the reference, "
               "unfiltered %.4f",
               ef, eu);
}

int main(void)
{
    test_mirror();
    test_lens();
    test_lens_wall();
    return unit_done();
}
