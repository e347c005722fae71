/* test_render_hyper.c - hypertexture: densities, modulation and the ray marcher
 *
 * Analytic cases: a homogeneous slab passes e^(-sigma d), a homogeneous ball e^(-sigma c)
 * for its chord c, along the marcher's own rays and in rendered pixels; the soft sphere's
 * density is the thesis's formula; bias and gain are exact at 0.5; an opaque sphere inside
 * a volume is seen through it, and a floor lit through a slab gets the light the slab
 * lets through; threads change no byte; bad input gets one line naming the scene line.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "lang/expr.h"
#include "render/hypertexture.h"
#include "render/scene.h"
#include "render/volume.h"
#include "fixtures.h"
#include "unit.h"

static struct tex_scene *parse(const char *text)
{
    struct tex_scene *s = tex_scene_parse(text, strlen(text), "test.scene");
    if (!s)
        printf("# parse: %s\n", tex_errmsg());
    return s;
}

/* A slab 0 <= z <= d of absorption sigma: e^(-sigma d / cos) along rays at any slant */
static void test_slab(void)
{
    const double sigma = 0.7, d = 1.3;
    char sc[1024];
    snprintf(sc, sizeof sc,
             "image 3 3 background 1 1 1 ambient 0 0 0\n"
             "camera { eye 0 0 -5 look 0 0 0 fov 0.01 }\n"
             "hypertexture { box { min -50 -50 0 max 50 50 %g } absorption %g step 0.1 }\n",
             d, sigma);
    struct tex_scene *s = parse(sc);
    CHECK(s != NULL, "slab: the scene parses");
    if (!s)
        return;
    double worst = 0;
    for (int i = 0; i < 8; i++) {
        double th = i * 0.15; /* up to 60 degrees */
        tex_v3 o = tex_v3_make(0, 0, -5), dir = tex_v3_make(sin(th), 0, cos(th));
        double tr = tex_volume_transmit(s, &o, &dir, 100);
        worst = fmax(worst, fabs(tr - exp(-sigma * d / cos(th))));
    }
    CHECKF(worst < 1e-4, "slab: transmittance e^(-sigma d / cos) at 8 slants (worst %.3g)", worst);
    tex_map *img = tex_render(s, NULL, NULL);
    CHECK(img != NULL, "slab: renders");
    if (img) {
        double px = tex_map_px(img, 1, 1)[0];
        CHECKF(fabs(px - exp(-sigma * d)) < 1e-4, "slab: the pixel is e^(-sigma d) (%.6f, want %.6f)",
               px, exp(-sigma * d));
        tex_map_free(img);
    }
    tex_scene_free(s);
}

/* A ball of radius 1, density 1 and no soft region: e^(-sigma 2 sqrt(1 - b^2)) at offset b */
static void test_ball(void)
{
    const double sigma = 1.1;
    char sc[1024];
    snprintf(sc, sizeof sc,
             "image 1 41 background 1 1 1 ambient 0 0 0\n"
             "camera { eye 0 0 -300 look 0 0 0 fov 0.01 }\n"
             "hypertexture { sphere { centre 0 0 0 radius 1 } absorption %g step 0.07 }\n",
             sigma);
    struct tex_scene *s = parse(sc);
    CHECK(s != NULL, "ball: the scene parses");
    if (!s)
        return;
    double worst = 0;
    for (int i = 0; i < 20; i++) {
        double b = i * 0.05;
        tex_v3 o = tex_v3_make(b, 0, -5), dir = tex_v3_make(0, 0, 1);
        double tr = tex_volume_transmit(s, &o, &dir, 10);
        worst = fmax(worst, fabs(tr - exp(-sigma * 2 * sqrt(1 - b * b))));
    }
    CHECKF(worst < 1e-4, "ball: transmittance of the chord 2 sqrt(1 - b^2) (worst %.3g)", worst);
    /* the rendered column: rays from far away, nearly parallel */
    tex_map *img = tex_render(s, NULL, NULL);
    if (img) {
        double half = tan(0.01 / 2 * M_PI / 180) * 300 * 41; /* the column's half height */
        worst = 0;
        for (int y = 0; y < 41; y++) {
            double b = fabs((1 - 2 * (y + 0.5) / 41) * half);
            double want = b < 1 ? exp(-sigma * 2 * sqrt(1 - b * b)) : 1;
            if (fabs(b - 1) > 0.02) /* the rim, where a slight slant changes the chord most */
                worst = fmax(worst, fabs(tex_map_px(img, 0, y)[0] - want));
        }
        CHECKF(worst < 1e-4, "ball: rendered pixels follow the chord (worst %.3g)", worst);
        tex_map_free(img);
    }
    tex_scene_free(s);
}

/* Thesis 2.9's D[c, r, s] along a line through the centre */
static void test_soft_sphere(void)
{
    struct tex_hdensity d = {.kind = TEX_HD_SPHERE, .centre = {0.5, -1, 2}, .radius = 1.2,
                             .soft = 0.6};
    struct tex_hdensity *bad;
    const char *msg;
    CHECK(tex_hdensity_prepare(&d, &bad, &msg) == 0, "soft sphere: prepares");
    double r1 = (1.2 - 0.3) * (1.2 - 0.3), r0 = (1.2 + 0.3) * (1.2 + 0.3), worst = 0;
    int ends = 1;
    for (int i = 0; i <= 200; i++) {
        double r = i * 0.01;
        tex_v3 P = tex_v3_make(0.5 + r * 0.6, -1 + r * 0.8, 2);
        double rx = r * r, want = rx <= r1 ? 1 : rx >= r0 ? 0 : (r0 - rx) / (r0 - r1);
        double got = tex_hdensity_eval(&d, &P);
        worst = fmax(worst, fabs(got - want));
        if (r < 0.89)
            ends &= got == 1;
        if (r > 1.51)
            ends &= got == 0;
    }
    CHECKF(worst < 1e-12, "soft sphere: D is (r0^2 - r^2) / (r0^2 - r1^2) in the soft region "
                          "(worst %.3g)", worst);
    CHECK(ends, "soft sphere: 1 inside r - s/2, 0 outside r + s/2");
    /* the soft booleans: max, min, min(a, 1 - b), 1 - a */
    struct tex_hdensity a = d, b = {.kind = TEX_HD_BOX, .min = {0, -2, 1}, .max = {2, 0, 3},
                                    .soft = 0.4};
    CHECK(tex_hdensity_prepare(&b, &bad, &msg) == 0, "soft box: prepares");
    struct tex_hdensity u = {.kind = TEX_HD_UNION, .a = &a, .b = &b},
                        n = {.kind = TEX_HD_INTERSECTION, .a = &a, .b = &b},
                        m = {.kind = TEX_HD_DIFFERENCE, .a = &a, .b = &b},
                        c = {.kind = TEX_HD_COMPLEMENT, .a = &a};
    int ok = 1;
    for (int i = 0; i < 50; i++) {
        tex_v3 P = tex_v3_make(-0.5 + i * 0.05, -1.2 + i * 0.01, 2 + 0.3 * sin(i));
        double x = tex_hdensity_eval(&a, &P), y = tex_hdensity_eval(&b, &P);
        ok &= tex_hdensity_eval(&u, &P) == fmax(x, y) && tex_hdensity_eval(&n, &P) == fmin(x, y) &&
              tex_hdensity_eval(&m, &P) == fmin(x, 1 - y) && tex_hdensity_eval(&c, &P) == 1 - x;
    }
    CHECK(ok, "soft booleans: union max, intersection min, difference min(a, 1 - b), "
              "complement 1 - a");
    CHECK(!tex_hdensity_bounded(&c) && tex_hdensity_bounded(&m) &&
              tex_hdensity_bounded(&(struct tex_hdensity){.kind = TEX_HD_INTERSECTION, .a = &c,
                                                          .b = &b}),
          "a complement is unbounded unless intersected");
}

static void test_bias_gain(void)
{
    int ok = 1;
    for (int i = 1; i < 100; i++) {
        double b = i / 100.0;
        ok &= tex_expr_op(TEX_EOP_BIAS, b, 0.5, 0) == b && tex_expr_op(TEX_EOP_GAIN, b, 0.5, 0) == 0.5;
    }
    CHECK(ok, "bias(b, 0.5) = b and gain(g, 0.5) = 0.5 exactly");
    CHECKF(fabs(tex_expr_op(TEX_EOP_BIAS, 0.3, 0.2, 0) - pow(0.2, log(0.3) / log(0.5))) < 1e-15 &&
               fabs(tex_expr_op(TEX_EOP_GAIN, 0.8, 0.2, 0) -
                    pow(0.4, log(0.2) / log(0.5)) / 2) < 1e-15,
           "bias is t^(ln b / ln 0.5), gain two bias curves");
}

/* The red of pixels (x, y) of scene sc into v, n of them: 1, or 0 where it does not render */
static int pixels(const char *sc, int n, const int (*xy)[2], double *v)
{
    tex_map *img = unit_render_text(sc, 0);
    for (int i = 0; img && i < n; i++)
        v[i] = tex_map_px(img, xy[i][0], xy[i][1])[0];
    tex_map_free(img);
    return img != NULL;
}

/* An opaque sphere of colour 1 (Ka Kd Ia) at the centre of an absorbing box: seen through
 * 1.5 units of it; the background through 4 */
static void test_inside(void)
{
    const double sigma = 0.4;
    static const int xy[2][2] = {{20, 20}, {0, 20}};
    char sc[1024];
    double v[2];
    snprintf(sc, sizeof sc,
             "image 41 41 background 1 1 1 ambient 1 1 1\n"
             "camera { eye 0 0 -5 look 0 0 0 fov 20 }\n"
             "surface lamp { Ka 1 Kd 1 Ks 0 }\n"
             "sphere { radius 0.5 surface lamp }\n"
             "hypertexture { box { min -2 -2 -2 max 2 2 2 } absorption %g step 0.05 }\n",
             sigma);
    if (!pixels(sc, 2, xy, v)) {
        CHECK(0, "inside: renders");
        return;
    }
    CHECKF(fabs(v[0] - exp(-sigma * 1.5)) < 1e-4,
           "inside: the sphere is seen through 1.5 units (%.6f, want %.6f)", v[0],
           exp(-sigma * 1.5));
    CHECKF(fabs(v[1] - exp(-sigma * 4 / cos(atan(tan(10 * M_PI / 180) * 40 / 41)))) < 1e-3,
           "inside: the background through the whole box (%.6f)", v[1]);
}

/* A floor under a distant light straight above, through a slab 1 <= y <= 2: Kd e^(-sigma) */
static void test_shadow(void)
{
    const double sigma = 0.9;
    static const int xy[1][2] = {{4, 4}};
    char sc[1024];
    double v = NAN;
    snprintf(sc, sizeof sc,
             "image 9 9 background 0 0 0 ambient 0 0 0\n"
             "camera { eye 0 0.5 -3 look 0 0 0 fov 10 }\n"
             "light distant { direction 0 1 0 }\n"
             "surface floor { Ka 0 Kd 0.5 Ks 0 }\n"
             "plane { normal 0 1 0 distance 0 surface floor }\n"
             "hypertexture { box { min -50 1 -50 max 50 2 50 } absorption %g scattering 0 }\n",
             sigma);
    CHECK(pixels(sc, 1, xy, &v), "shadow: renders");
    CHECKF(fabs(v - 0.5 * exp(-sigma)) < 1e-4,
           "shadow: the light through the slab is e^(-sigma) (%.6f, want %.6f)", v,
           0.5 * exp(-sigma));
}

static const char *smoke =
    "image 24 18 samples 2 ambient 0.3 0.3 0.3 background 0.2 0.25 0.3\n"
    "camera { eye 0 1.5 -5 look 0 0.6 0 fov 45 }\n"
    "light point { position -3 5 -3 }\n"
    "light area { position 2 4 -2 edge1 0.5 0 0 edge2 0 0 0.5 samples 2 intensity 0.4 }\n"
    "texture turb turbulence { solid frequency 1.5 octaves 4 seed 7 }\n"
    "surface red { Kd 0.8 0.2 0.1 Ks 0.3 n 40 Kr 0.2 }\n"
    "plane { normal 0 1 0 distance 0 }\n"
    "sphere { centre 0 0.7 0 radius 0.5 surface red }\n"
    "hypertexture {\n"
    "    difference { box { min -1.2 0 -1.2 max 1.2 1.6 1.2 soft 0.5 }\n"
    "                 sphere { centre 0 0.7 0 radius 0.55 soft 0.1 } }\n"
    "    H = gain(0.7, D * (0.4 + turb))\n"
    "    absorption 0.5 scattering 3 phase 0.3 step 0.06\n"
    "    colour = mix(0.5 0.5 0.6, 1 1 1, H) emission = 0.2 0.1 0 * H\n"
    "}\n";

static void test_threads(void)
{
    tex_map *a = unit_render_text(smoke, 1), *b = unit_render_text(smoke, 2);
    CHECK(a && b, "threads: renders");
    if (a && b) {
        int same = !memcmp(a->px, b->px, tex_map_samples(a) * sizeof *a->px);
        double sum = 0;
        for (size_t i = 0; i < tex_map_samples(a); i++)
            sum += a->px[i];
        CHECK(same, "threads: -j1 and -j2 give the same bytes");
        CHECKF(isfinite(sum) && sum > 0, "threads: the image is finite and lit (%g)", sum);
    }
    tex_map_free(a);
    tex_map_free(b);
    /* a spectral scene: not broken */
    char sc[2048];
    snprintf(sc, sizeof sc, "colour spectral 8\n%s", smoke);
    tex_map *c = unit_render_text(sc, 0);
    int fine = c != NULL;
    for (size_t i = 0; c && i < tex_map_samples(c); i++)
        fine &= isfinite(c->px[i]) && c->px[i] >= 0;
    CHECK(fine, "spectral: the volume renders, finite");
    tex_map_free(c);
}

/* Bad input: "test.scene:LINE:COL: ..." naming the culprit, and a range where there is one */
static void bad(const char *body, const char *where, const char *what)
{
    char sc[1024];
    snprintf(sc, sizeof sc, "image 4 4\n%s\n", body);
    struct tex_scene *s = tex_scene_parse(sc, strlen(sc), "test.scene");
    const char *m = s ? "" : tex_errmsg();
    CHECKF(!s && strstr(m, where) && strstr(m, what) && !strchr(m, '\n'), "bad input: %s", m);
    tex_scene_free(s);
}

static void test_bad(void)
{
    bad("hypertexture { sphere { } step 0 }", "test.scene:2:32:", "step must be 1e-06..1000000 (got 0)");
    bad("hypertexture { sphere { }\n absorption -1 }", "test.scene:3:13:", "absorption must be");
    bad("hypertexture { complement { sphere { } } }", "test.scene:2:1:", "unbounded volume");
    bad("hypertexture { sphere { radius 1 soft 3 } }", "test.scene:2:16:", "soft width");
    bad("hypertexture { box { min 0 0 0 max 0 1 1 } }", "test.scene:2:16:", "min < max");
    bad("hypertexture { sphere { }\n density = H * 2 }", "test.scene:3:12:", "density makes H");
    bad("hypertexture { sphere { } H = 2 * H }", "test.scene:2:35:", "density makes H");
    bad("hypertexture { sphere { } colour = ndotv }", "test.scene:2:36:", "surface's");
    bad("hypertexture { sphere { } box { } }", "test.scene:2:27:", "one density");
    bad("hypertexture { step 0.1 }", "test.scene:2:1:", "needs a density");
    bad("hypertexture { sphere { } absorbtion 1 }", "test.scene:2:27:", "did you mean absorption");
    /* never spins: a huge volume at the finest step renders, its steps capped */
    tex_map *img = unit_render_text("image 4 4 camera { eye 0 0 -5 look 0 0 0 fov 0.01 }\n"
                                    "hypertexture { box { min -1e5 -1e5 -1e5 max 1e5 1e5 1e5 } "
                                    "absorption 1e-9 step 1e-6 }\n", 0);
    CHECK(img != NULL, "a huge volume at the finest step renders (steps capped)");
    tex_map_free(img);
    img = unit_render_text("image 2 2 camera { eye 0 0 -5 look 0 0 0 fov 0.01 }\n"
                           "light point { position 0 3 0 }\n"
                           "hypertexture { box { min -1e5 -1e5 -1e5 max 1e5 1e5 1e5 } "
                           "absorption 0 scattering 1e-9 step 1e-6 shadow-step 1e-6 }\n", 1);
    CHECK(img != NULL, "and scattering toward a light through it: shadow rays capped too");
    tex_map_free(img);
    /* a span 16 long at 1e17, where a double's resolution is 16: the marches end */
    struct tex_scene *s = parse("image 2 2 camera { eye 0 0 0 look 0 0 1 fov 0.01 }\n"
                                "hypertexture { box { min -1e3 -1e3 1e17 max 1e3 1e3 "
                                "100000000000000016 } absorption 0 step 1e-6 shadow-step 1e-6 }\n");
    if (s) {
        tex_v3 o = tex_v3_make(0, 0, 2e17), d = tex_v3_make(0, 0, -1);
        CHECK(tex_volume_transmit(s, &o, &d, 2e17) == 1,
              "a shadow ray through a span below a double's resolution ends");
        tex_map *m = tex_render(s, NULL, NULL);
        CHECK(m != NULL, "and an eye ray's march through it");
        tex_map_free(m);
        tex_scene_free(s);
    }
}

int main(void)
{
    test_slab();
    test_ball();
    test_soft_sphere();
    test_bias_gain();
    test_inside();
    test_shadow();
    test_threads();
    test_bad();
    return unit_done();
}
