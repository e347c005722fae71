/* test_render_media.c - nested transparent media: Snell at every interface
 *
 * Concentric balls (outer radius 1, inner 0.5) in front of a striped
 * backdrop, seen through one column of pixels.  A 2D tracer here follows
 * each pixel's ray with the indices on both sides taken from where the
 * points lie (the truth), and predicts which stripe it lands on; the
 * renderer must agree on every row.  The same tracer with air assumed
 * outside every surface (the old rule) must disagree on many rows, so the
 * test can tell the two apart.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "render/scene.h"
#include "fixtures.h"
#include "unit.h"

#define W 9
#define H 301
#define EYE 20.0
#define BACK 4.0   /* the backdrop's front face, z */
#define THICK 1e-3 /* its stripes' thickness: slanted rays may meet their sides */
#define DEPTH 10

static double fov(void)
{
    double sy = 1.15 / EYE, sx = sy * W / H;
    return 2 * atan(sx) * 180 / M_PI;
}

/* White stripes y in [0.25 k, 0.25 k + 0.125), k = -8..8; *edge: too near a
 * border to tell (a ray of slope dy/dz may meet a stripe's side). */
static int white(double y, double slope, int *edge)
{
    double q = (y + 2) / 0.125;
    *edge = fabs(q - floor(q + 0.5)) * 0.125 < 1e-4 + THICK * fabs(slope);
    return y >= -2 && y < 2.25 && fmod(y + 2, 0.25) < 0.125;
}

/* 2D (y, z) ray tracer: circles of radius a (index na) and b < a (index nb)
 * about the origin.  naive: every surface has air on its outside.
 * Returns the landing height on the backdrop (*slope: the ray's dy/dz there),
 * or NAN if the ray is lost. */
static double land(double y0, double z0, double dy, double dz, double a, double na, double b,
                   double nb, int naive, double *slope)
{
    double rad[2] = {a, b}, idx[2] = {na, nb};
    for (int ev = 0; ev < DEPTH - 1; ev++) {
        /* nearest circle crossing ahead */
        double best = INFINITY;
        int which = -1;
        for (int c = 0; c < 2; c++) {
            double bq = y0 * dy + z0 * dz, cq = y0 * y0 + z0 * z0 - rad[c] * rad[c];
            double disc = bq * bq - cq;
            if (disc <= 0)
                continue;
            double q = sqrt(disc);
            double ts[2] = {-bq - q, -bq + q};
            for (int k = 0; k < 2; k++)
                if (ts[k] > 1e-9 && ts[k] < best)
                    best = ts[k], which = c;
        }
        if (which < 0) {
            *slope = dy / dz;
            return dz > 0 ? y0 + (BACK - z0) / dz * dy : NAN;
        }
        y0 += best * dy, z0 += best * dz;
        double ny = y0 / rad[which], nz = z0 / rad[which]; /* outward */
        int inward = ny * dy + nz * dz < 0;
        double n1, n2;
        if (naive) {
            n1 = inward ? 1 : idx[which];
            n2 = inward ? idx[which] : 1;
        } else {
            /* the index just inside / outside this circle */
            double in = idx[which], out = which == 1 ? na : 1;
            n1 = inward ? out : in;
            n2 = inward ? in : out;
        }
        if (!inward)
            ny = -ny, nz = -nz; /* now facing against the ray */
        double cosi = -(ny * dy + nz * dz);
        double ty = dy + cosi * ny, tz = dz + cosi * nz, tl = hypot(ty, tz); /* tangent */
        double sint = n1 / n2 * tl;
        if (sint > 1) { /* total internal reflection */
            dy += 2 * cosi * ny, dz += 2 * cosi * nz;
            continue;
        }
        double cost = sqrt(1 - sint * sint);
        if (tl > 0)
            ty /= tl, tz /= tl;
        dy = sint * ty - cost * ny;
        dz = sint * tz - cost * nz;
    }
    return NAN;
}

static void test_nested(const char *what, double na, double nb)
{
    char sc[4096];
    int len = snprintf(sc, sizeof sc,
                       "image %d %d samples 1 depth %d ambient 1 1 1 background 0 0 0\n"
                       "camera { eye 0 0 %g look 0 0 0 fov %.12f }\n"
                       "surface outer { Ka 0 Kd 0 Ks 0 Kr 0 Kt 1 ior %g }\n"
                       "surface inner { Ka 0 Kd 0 Ks 0 Kr 0 Kt 1 ior %g }\n"
                       "surface white { Ka 1 Kd 1 Ks 0 }\n"
                       "sphere { radius 1 surface outer }\n"
                       "sphere { radius 0.5 surface inner }\n",
                       W, H, DEPTH, -EYE, fov(), na, nb);
    for (int k = -8; k <= 8; k++)
        len += snprintf(sc + len, sizeof sc - len,
                        "box { min -50 %g %g max 50 %g %g surface white }\n", 0.25 * k, BACK,
                        0.25 * k + 0.125, BACK + THICK);
    tex_map *img = unit_render_text(sc, 0);
    CHECKF(img != NULL, "%s: scene parses and renders", what);
    if (!img)
        return;
    double sy = tan(fov() * M_PI / 360) * H / W;
    int rows = 0, through = 0, wrong = 0, naive_wrong = 0, first_bad = -1;
    for (int y = 0; y < H; y++) {
        double b = (1 - 2 * (y + 0.5) / H) * sy, l = hypot(b, 1);
        double dy = b / l, dz = 1 / l;
        double sl, sn;
        double yl = land(0, -EYE, dy, dz, 1, na, 0.5, nb, 0, &sl);
        double yn = land(0, -EYE, dy, dz, 1, na, 0.5, nb, 1, &sn);
        int edge, edge_n;
        if (isnan(yl))
            continue;
        int want = white(yl, sl, &edge), naive = isnan(yn) ? 0 : white(yn, sn, &edge_n);
        if (edge)
            continue;
        rows++;
        through += fabs(b * EYE / l) < 0.5; /* aimed at the inner ball */
        int got = tex_map_px(img, W / 2, y)[0] > 0.5f;
        if (got != want) {
            wrong++;
            if (first_bad < 0)
                first_bad = y;
        }
        naive_wrong += naive != got;
    }
    CHECKF(rows > H * 9 / 10 && through > 50 && wrong == 0,
           "%s: every row lands where Snell at each interface predicts (%d rows, %d wrong, "
           "first %d)",
           what, rows, wrong, first_bad);
    CHECKF(naive_wrong > 10, "%s: air outside every surface would differ on %d rows", what,
           naive_wrong);
    tex_map_free(img);
}

static void test_stack(void)
{
    struct tex_object water = {0}, glass = {0}, other = {0};
    struct tex_media a, b, c, d;
    double n1, n2, seen[8];
    tex_media_cross(NULL, &water, 1, 1.33, &a, &seen[0], &seen[1]);
    tex_media_cross(&a, &glass, 1, 1.5, &b, &seen[2], &seen[3]);
    tex_media_cross(&b, &glass, 0, 1.5, &c, &seen[4], &seen[5]);
    tex_media_cross(&c, &water, 0, 1.33, &d, &seen[6], &seen[7]);
    double want[8] = {1, 1.33, 1.33, 1.5, 1.5, 1.33, 1.33, 1};
    CHECK(!memcmp(seen, want, sizeof want) && d.n == 0,
          "the stack: air -> water -> glass -> water -> air");
    /* overlapping solids: leave the outer one first */
    tex_media_cross(&b, &water, 0, 1.33, &c, &n1, &n2);
    CHECKF(c.n == 1 && c.ob[0] == &glass && n1 == 1.33 && n2 == 1.5,
           "leaving a solid that is not the innermost removes it where it lies (%g -> %g)", n1,
           n2);
    tex_media_cross(&a, &other, 0, 2, &c, &n1, &n2);
    CHECKF(c.n == 1 && n1 == 2 && n2 == 1.33, "leaving a solid never entered keeps the stack");
    c.n = 0;
    for (int i = 0; i < TEX_MEDIA_MAX + 3; i++) {
        tex_media_cross(&c, &other, 1, 1 + i, &d, &n1, &n2);
        c = d;
    }
    CHECKF(c.n == TEX_MEDIA_MAX && tex_media_ior(&c) == TEX_MEDIA_MAX + 3,
           "a full stack forgets the outermost medium (%d, innermost %g)", c.n,
           tex_media_ior(&c));
}

/* The camera under water: a ball of the water's own index is invisible
 * from inside the water (rays cross it unbent), so the stripes look the
 * same with and without it.  Were the camera taken to be in air, the ball
 * would be a 1 -> 1.33 lens and move them. */
static void test_camera_inside(void)
{
    static const char head[] =
        "image 48 48 samples 1 depth 10 ambient 1 1 1 background 0 0 0\n"
        "camera { eye 0 0 -20 look 0 0 0 fov 12 }\n"
        "surface water { Ka 0 Kd 0 Ks 0 Kr 0 Kt 1 ior 1.33 }\n"
        "surface white { Ka 1 Kd 1 Ks 0 }\n"
        "sphere { radius 100 surface water }\n";
    char sc[2][4096];
    for (int k = 0; k < 2; k++) {
        int len = snprintf(sc[k], sizeof sc[k], "%s%s", head,
                           k ? "sphere { radius 1.5 surface water }\n" : "");
        for (int j = -8; j <= 8; j++)
            len += snprintf(sc[k] + len, sizeof sc[k] - len,
                            "box { min -50 %g 4 max 50 %g 4.001 surface white }\n", 0.25 * j,
                            0.25 * j + 0.125);
    }
    tex_map *a = unit_render_text(sc[0], 0), *b = unit_render_text(sc[1], 0);
    CHECKF(a && b, "camera in water: both scenes render");
    if (!a || !b) {
        tex_map_free(a);
        tex_map_free(b);
        return;
    }
    int differ = 0, white = 0;
    for (size_t i = 0; i < tex_map_samples(a); i++) {
        differ += fabsf(a->px[i] - b->px[i]) > 1e-3f;
        white += a->px[i] > 0.5f;
    }
    CHECKF(differ == 0 && white > 500,
           "camera in water: a water-index ball is invisible (%d of %zu samples differ, %d white)",
           differ, tex_map_samples(a), white);
    tex_map_free(a);
    tex_map_free(b);
}

int main(void)
{
    test_camera_inside();
    test_stack();
    test_nested("glass ball (1.5) inside a water ball (1.33)", 1.33, 1.5);
    test_nested("air bubble (1.0) inside a glass ball (1.5)", 1.5, 1.0);
    return unit_done();
}
