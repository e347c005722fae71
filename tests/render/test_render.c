/* test_render.c - analytic checks of t_apply's renderer */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"
#include "io/file.h"
#include "render/box4.h"
#include "render/bvh.h"
#include "render/camera.h"
#include "render/scene.h"
#include "render/appfn.h"
#include "render/footprint.h"
#include "render/whitted.h"
#include "render/x86/bvh_x86.h"
#include "render/x86/light_x86.h"
#include "render/x86/packet_x86.h"
#include "base/rng.h"
#include "base/simd.h"
#include "fixtures.h"
#include "unit.h"

static char dir[] = "/tmp/textura-render.XXXXXX";

static void test_silhouette(void)
{
    const char *sc = "image 200 200 samples 4 ambient 1 1 1 background 0 0 0\n"
                     "camera { eye 0 0 -10 look 0 0 0 fov 30 }\n"
                     "surface white { Ka 1 Kd 1 1 1 }\n"
                     "sphere { radius 1 surface white }\n";
    tex_map *m = unit_render_text(sc, 0);
    CHECK(m != NULL, "sphere scene renders");
    if (!m)
        return;
    double area = 0;
    for (size_t i = 0; i < (size_t)m->w * m->h; i++)
        area += m->px[3 * i];
    double rho = tan(asin(1.0 / 10)), ppu = 200 / (2 * tan(15 * M_PI / 180));
    double want = M_PI * rho * ppu * rho * ppu;
    CHECKF(fabs(area - want) < 0.01 * want, "sphere silhouette %.1f px vs projected disc %.1f px",
           area, want);
    tex_map_free(m);
}

static void test_lambert(void)
{
    const char *sc = "image 32 32 ambient 0 0 0\n"
                     "camera { eye 0 5 -5 look 0 0 0 fov 20 }\n"
                     "light distant { direction 0 1 1 }\n"
                     "surface matte { Ka 0 Kd 1 1 1 Ks 0 }\n"
                     "plane { surface matte }\n";
    tex_map *m = unit_render_text(sc, 0);
    CHECK(m != NULL, "plane scene renders");
    if (!m)
        return;
    double worst = 0;
    for (size_t i = 0; i < tex_map_samples(m); i++)
        worst = fmax(worst, fabs(m->px[i] - M_SQRT1_2));
    CHECKF(worst < 1e-5, "Lambertian plane equals N.L = 0.7071 (worst error %g)", worst);
    tex_map_free(m);
}

static void test_shadow(void)
{
    const char *sc = "image 41 41 ambient 1 1 1\n"
                     "camera { eye 0 3 -6 look 0 0 0 fov 30 }\n"
                     "light distant { direction 0 1 0 }\n"
                     "surface matte { Ka 0.2 Kd 1 1 1 Ks 0 }\n"
                     "plane { surface matte }\n"
                     "sphere { centre 0 1 0 radius 0.5 surface matte }\n";
    tex_map *m = unit_render_text(sc, 0);
    CHECK(m != NULL, "shadow scene renders");
    if (!m)
        return;
    float c = tex_map_px(m, 20, 20)[0], lit = tex_map_px(m, 2, 38)[0];
    CHECKF(fabsf(c - 0.2f) < 1e-5, "point in shadow is at the ambient level (%g)", c);
    CHECKF(fabsf(lit - 1.2f) < 1e-4, "point out of shadow is ambient + N.L (%g)", lit);
    tex_map_free(m);
}

/* A ray at height h through a glass sphere (ior 1.5): the chord inside spans
 * pi - 2 theta_t around the centre, and the total deviation is 2 (theta_i - theta_t). */
static void test_snell(void)
{
    double h = 0.5, ior = 1.5;
    double ti = asin(h), tt = asin(h / ior);
    struct tex_object ob = {0};
    ob.op = TEX_CSG_LEAF;
    ob.kind = TEX_SHAPE_SPHERE;
    tex_xform_identity(&ob.to_world);
    tex_xform_identity(&ob.to_obj);
    tex_v3 o = tex_v3_make(0, h, -5), d = tex_v3_make(0, 0, 1);
    struct tex_spans s;
    tex_object_spans(&ob, o, d, &s);
    CHECK(s.n == 1, "ray meets the sphere");
    tex_v3 p1 = tex_v3_madd(o, d, s.in[0].t), n1 = tex_v3_norm(p1), t1, t2;
    CHECK(tex_refract(d, n1, 1, ior, &t1), "refracts on entry");
    tex_object_spans(&ob, tex_v3_madd(p1, t1, 1e-9), t1, &s);
    tex_v3 p2 = tex_v3_madd(tex_v3_madd(p1, t1, 1e-9), t1, s.out[0].t);
    double chord = acos(tex_v3_dot(n1, tex_v3_norm(p2)));
    CHECKF(fabs(chord - (M_PI - 2 * tt)) < 1e-9, "exit point %.9f rad around vs Snell %.9f",
           chord, M_PI - 2 * tt);
    tex_v3 n2 = tex_v3_scale(tex_v3_norm(p2), -1); /* inside, facing the ray */
    CHECK(tex_refract(t1, n2, ior, 1, &t2), "leaves the sphere");
    double dev = acos(tex_v3_dot(d, t2));
    CHECKF(fabs(dev - 2 * (ti - tt)) < 1e-9, "deviation %.9f vs 2(ti - tt) = %.9f", dev,
           2 * (ti - tt));
    tex_v3 g = tex_v3_make(0, sin(1.2), cos(1.2)), gn = tex_v3_make(0, 0, -1);
    CHECK(!tex_refract(g, gn, 1.5, 1, &t2), "total internal reflection beyond the critical angle");
}

static void test_difference(void)
{
    const char *fmt = "image 200 200 ambient 1 1 1 background 0 0 0\n"
                      "camera { eye 0 0 -100 look 0 0 0 fov 2 }\n"
                      "surface white { Ka 1 Kd 1 1 1 }\n%s";
    char sc[1024];
    snprintf(sc, sizeof sc, fmt,
             "difference { box { min -1 -1 -1 max 1 1 1 } "
             "cylinder { base 0 0 -2 top 0 0 2 radius 0.5 } surface white }\n");
    tex_map *m = unit_render_text(sc, 0);
    CHECK(m != NULL, "CSG difference renders");
    if (!m)
        return;
    double ppu = 200 / (2 * tan(M_PI / 180)), hole = 0;
    for (int y = 0; y < 200; y++)
        for (int x = 0; x < 200; x++)
            if (fabs(x + 0.5 - 100) < 0.9 * ppu * 1 / 99 && fabs(y + 0.5 - 100) < 0.9 * ppu / 99)
                hole += tex_map_px(m, x, y)[0] < 0.5;
    double r = 0.5 / 101 * ppu, want = M_PI * r * r;
    CHECKF(fabs(hole - want) < 0.04 * want, "hole through the box %.0f px vs %.0f px", hole, want);
    tex_map_free(m);
}

static char *write_map(tex_map *m, const char *name)
{
    static char path[4][256];
    static int k;
    char *p = path[k++ & 3];
    snprintf(p, 256, "%s/%s", dir, name);
    struct tex_write_opts o = TEX_WRITE_DEFAULTS;
    if (tex_map_write(m, p, &o) < 0)
        printf("# write: %s\n", tex_errmsg());
    return p;
}

static tex_map *checker(int n, int cells_u, int cells_v)
{
    tex_map *m = tex_map_new(n, n, 1);
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++)
            tex_map_px(m, x, y)[0] = (float)(((x * cells_u / n) + (y * cells_v / n)) & 1);
    return m;
}

static void test_sphere_map(void)
{
    struct tex_texture t = {0};
    t.mip = malloc(sizeof *t.mip);
    t.mip[0] = checker(256, 16, 8);
    t.nlevels = 1;
    int changes = 0;
    float prev = -1;
    for (int i = 0; i <= 3600; i++) {
        double a = 2 * M_PI * (i + 0.25) / 3600, u, v;
        tex_shape_methods[TEX_SHAPE_SPHERE].uv(NULL, tex_v3_make(cos(a), 0.01, sin(a)), &u, &v);
        float f[3];
        tex_texture_eval(&t, u, v, 0, 0, f);
        float b = f[0] > 0.5f;
        if (prev >= 0 && b != prev)
            changes++;
        prev = b;
    }
    CHECKF(changes == 16, "sphere_map of a 16x8 checker: %d checks along the equator", changes);
    tex_map_free(t.mip[0]);
    free(t.mip);
}

static void test_kd_f(void)
{
    tex_map *m = tex_map_new(64, 64, 1);
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++)
            tex_map_px(m, x, y)[0] = (float)(0.5 + 0.4 * sin(x * 0.3) * cos(y * 0.17));
    char *path = write_map(m, "f.exr");
    char sc[1024];
    snprintf(sc, sizeof sc,
             "image 64 64 ambient 0 0 0\n"
             "camera { eye 0.5 10 0.5 look 0.5 0 0.5 up 0 0 1 fov %.10f }\n"
             "light distant { direction 0 1 0 }\n"
             "texture t file \"%s\"\n"
             "surface s { Ka 0 Ks 0 apply t { Kd = f } }\n"
             "plane { surface s }\n",
             2 * atan(0.05) * 180 / M_PI, path);
    tex_map *img = unit_render_text(sc, 0);
    CHECK(img != NULL, "Kd = f scene renders");
    if (img) {
        double worst = 0;
        for (int y = 0; y < 64; y++)
            for (int x = 0; x < 64; x++)
                worst = fmax(worst, fabs(tex_map_px(img, x, y)[1] - tex_map_px(m, x, 63 - y)[0]));
        CHECKF(worst < 2e-3, "Kd = f reproduces the map on an evenly lit plane (worst %g)", worst);
    }
    tex_map_free(img);
    tex_map_free(m);
}

static void test_determinism(void)
{
    const char *sc = "image 64 48 samples 4 ambient 0.2 0.2 0.2\n"
                     "camera { eye 0 2 -6 look 0 0.5 0 }\n"
                     "light area { position -1 5 -3 edge1 2 0 0 edge2 0 0 2 samples 3 }\n"
                     "surface g { Kd 0.1 Ks 0.8 n 80 Kr 0.2 Kt 0.7 ior 1.5 }\n"
                     "plane { }\n"
                     "sphere { centre 0 1 0 surface g }\n";
    tex_map *a = unit_render_text(sc, 1), *b = unit_render_text(sc, 2);
    CHECK(a && b && !memcmp(a->px, b->px, tex_map_samples(a) * sizeof(float)),
          "the same bytes with 1 and 2 threads");
    tex_map_free(a);
    tex_map_free(b);
}

static void test_receding(void)
{
    tex_map *m = checker(64, 2, 2);
    char *path = write_map(m, "chk.exr");
    tex_map_free(m);
    double var[2];
    for (int filter = 0; filter < 2; filter++) {
        char sc[1024];
        snprintf(sc, sizeof sc,
                 "image 160 120 ambient 1 1 1 filter %s background 0.5 0.5 0.5\n"
                 "camera { eye 0 1 0 look 0 0.9 10 fov 60 }\n"
                 "texture c file \"%s\"\n"
                 "surface s { Ka 1 Kd 1 1 1 apply c { Kd = f } }\n"
                 "plane { surface s }\n",
                 filter ? "on" : "off", path);
        tex_map *img = unit_render_text(sc, 0);
        if (!img) {
            var[filter] = 1;
            continue;
        }
        /* the far rows: just below the horizon (which lies at row ~58.6) */
        double s = 0, s2 = 0;
        int n = 0;
        for (int y = 61; y < 68; y++)
            for (int x = 0; x < 160; x++) {
                double v = tex_map_px(img, x, y)[0];
                s += v, s2 += v * v, n++;
            }
        var[filter] = s2 / n - (s / n) * (s / n);
        tex_map_free(img);
    }
    CHECKF(var[1] < 0.01 && var[1] < var[0] / 4,
           "receding checkerboard far rows: variance %.4f filtered vs %.4f unfiltered", var[1],
           var[0]);
}

/* The first boundary of ob beyond tmin: what a search over every object finds. */
static int brute_first(const struct tex_object *ob, tex_v3 o, tex_v3 d, double tmin,
                       struct tex_hit *h)
{
    struct tex_spans s;
    tex_object_spans(ob, o, d, &s);
    for (int i = 0; i < s.n; i++) {
        const struct tex_hit *x = s.in[i].t > tmin ? &s.in[i] : s.out[i].t > tmin ? &s.out[i] : NULL;
        if (!x)
            continue;
        if (!x->leaf)
            return 0;
        *h = *x;
        return 1;
    }
    return 0;
}

/* A unit direction drawn from g, its components in order */
static tex_v3 random_dir(tex_rng *g)
{
    double x = tex_rng_uniform(g) - 0.5, y = tex_rng_uniform(g) - 0.5;
    return tex_v3_norm(tex_v3_make(x, y, tex_rng_uniform(g) - 0.5));
}

/* The closest hit along o + t d beyond 0 among every object of s, each searched: *best
 * (leaf NULL where none) */
static void brute_closest(const struct tex_scene *s, tex_v3 o, tex_v3 d, struct tex_hit *best)
{
    struct tex_hit h;
    *best = (struct tex_hit){INFINITY, NULL, 0};
    for (int i = 0; i < s->nobjects; i++)
        if (brute_first(s->objects[i], o, d, 0, &h) && h.t < best->t)
            *best = h;
}

/* 600 objects of every fast path and a tilted plane, placed by g, prepared; twins: each
 * sphere of the world-space path twice, in one place, and each box with a larger one on its
 * lowest corner, rotated alike (ties: rays entering both at one face) */
static struct tex_scene *bvh_scene(tex_rng *g, int twins)
{
    size_t cap = 200000, len = 0;
    char *sc = malloc(cap);
    if (!sc)
        return NULL;
    len += snprintf(sc + len, cap - len, "image 8 8 camera { eye 0 0 -30 look 0 0 0 }\n"
                                         "plane { normal 0.1 1 0.2 distance -12 }\n");
    for (int i = 0; i < 600; i++) {
        double x = 20 * tex_rng_uniform(g) - 10, y = 20 * tex_rng_uniform(g) - 10,
               z = 20 * tex_rng_uniform(g) - 10, r = 0.2 + 0.8 * tex_rng_uniform(g);
        switch (i % 6) {
        case 0: /* world-space fast path */
            for (int k = 0; k <= twins; k++)
                len += snprintf(sc + len, cap - len, "sphere { centre %g %g %g radius %g }\n", x,
                                y, z, r);
            break;
        case 1: /* rotated and uniformly scaled: still the fast path */
            len += snprintf(sc + len, cap - len,
                            "sphere { radius %g rotate 10 20 30 scale 1.5 translate %g %g %g }\n",
                            r, x, y, z);
            break;
        case 2: /* an ellipsoid: the transformed path */
            len += snprintf(sc + len, cap - len,
                            "sphere { radius %g scale 1 0.5 2 rotate 0 40 0 translate %g %g %g }\n",
                            r, x, y, z);
            break;
        case 3:
            for (int k = 0; k <= twins; k++) /* the twin larger, from the same corner */
                len += snprintf(sc + len, cap - len,
                                "box { min %g %g %g max %g %g %g rotate 5 5 5 }\n", x, y, z,
                                x + (1 + 3 * k) * r, y + (2 + 3 * k) * r, z + (1 + 3 * k) * r);
            break;
        case 4:
            len += snprintf(sc + len, cap - len,
                            "cylinder { base %g %g %g top %g %g %g radius %g }\n", x, y, z, x + 1,
                            y + 1, z, r / 2);
            break;
        default:
            len += snprintf(sc + len, cap - len,
                            "difference { sphere { centre %g %g %g radius %g } "
                            "box { min %g %g %g max %g %g %g } }\n",
                            x, y, z, r, x, y - 1, z - 1, x + 1, y + 1, z + 1);
            break;
        }
    }
    struct tex_scene *s = tex_scene_parse(sc, len, "bvh.scene");
    free(sc);
    if (s && tex_scene_prepare(s) != 0) {
        tex_scene_free(s);
        s = NULL;
    }
    return s;
}

/* Rays from the eye whose directions project outside the box's view meet no bounded object
 * (a search of every object), and tracing the unbounded alone answers the same. */
static void check_view(const struct tex_scene *s, tex_rng *g)
{
    struct tex_view vw;
    tex_v3 eye = tex_v3_make(0, 0, -30);
    int seen = tex_scene_view(s, eye, tex_v3_make(1, 0, 0), tex_v3_make(0, 1, 0),
                              tex_v3_make(0, 0, 1), &vw), culled = 0, wrong = 0;
    for (int k = 0; seen && k < 3000; k++) {
        double x = 2 * tex_rng_uniform(g) - 1, y = 2 * tex_rng_uniform(g) - 1;
        tex_v3 d = tex_v3_norm(tex_v3_make(x, y, 1));
        double a = d.x / d.z, b = d.y / d.z;
        if (a >= vw.rect[0] && a <= vw.rect[1] && b >= vw.rect[2] && b <= vw.rect[3])
            continue;
        culled++;
        struct tex_hit h, u, best;
        brute_closest(s, eye, d, &best);
        int fu = tex_scene_trace_unbounded(s, &eye, &d, 0, INFINITY, &u);
        int ft = tex_scene_trace(s, &eye, &d, 0, INFINITY, NULL, &h);
        wrong += (best.leaf && tex_object_top(best.leaf)->bounded) || fu != ft ||
                 (fu && (u.t != h.t || u.leaf != h.leaf));
    }
    CHECKF(seen && culled > 300 && wrong == 0,
           "rays beside the objects' box seen from the eye meet no bounded object (%d of %d wrong)",
           wrong, culled);
}

/* The BVH (with its fast paths for spheres and planes) finds the same closest
 * hit as testing every object, and shadow queries agree on occlusion. */
static void test_bvh_brute(void)
{
    tex_rng g;
    tex_rng_seed(&g, 42);
    struct tex_scene *s = bvh_scene(&g, 0);
    CHECK(s != NULL, "600-object scene prepares");
    if (!s)
        return;
    int bad_closest = 0, bad_any = 0, hits = 0;
    for (int k = 0; k < 3000; k++) {
        tex_v3 o = tex_v3_make(30 * tex_rng_uniform(&g) - 15, 30 * tex_rng_uniform(&g) - 15,
                               30 * tex_rng_uniform(&g) - 15);
        tex_v3 d = random_dir(&g);
        if (k % 10 == 0)
            d = tex_v3_make(0, 0, k % 20 ? 1 : -1); /* axis-aligned: zero components */
        struct tex_hit best, h;
        brute_closest(s, o, d, &best);
        int found = tex_scene_trace(s, &o, &d, 0, INFINITY, NULL, &h);
        hits += found;
        if (found != (best.leaf != NULL) ||
            (found && (fabs(h.t - best.t) > 1e-9 * (1 + best.t) ||
                       (h.leaf != best.leaf && fabs(h.t - best.t) > 1e-12))))
            bad_closest++;
        double tmax = best.leaf ? best.t * 1.5 : 40; /* occluded iff something lies before tmax */
        struct tex_hit a;
        int occl = tex_bvh_trace_any(s->bvh, &o, &d, 0, tmax, 1, &a);
        if (occl != (best.leaf != NULL) || (occl && !(a.t > 0 && a.t < tmax)))
            bad_any++;
    }
    CHECKF(bad_closest == 0 && hits > 1000,
           "BVH closest hits match a search of every object (%d of 3000 differ, %d hits)",
           bad_closest, hits);
    CHECKF(bad_any == 0, "BVH shadow queries match (%d of 3000 differ)", bad_any);
    check_view(s, &g);
    tex_scene_free(s);
}

/* A coordinate for the box tests: on a grid of 0.5 most of the time, so that origins lie on
 * boxes' faces and boxes are flat (+-0 and ties in the slabs' min and max) */
static double box_coord(tex_rng *g)
{
    return tex_rng_below(g, 4) ? 0.5 * ((int)tex_rng_below(g, 9) - 4) : 4 * tex_rng_uniform(g) - 2;
}

/* The tree's four-box test in SSE2's and AVX2's lanes gives tex_box4_hit's bits: which
 * boxes are entered and at what distance, for rays along the axes, from the faces, into
 * flat boxes and empty ones */
static void test_box4_lanes(void)
{
#ifdef TEX_X86
    tex_rng g;
    tex_rng_seed(&g, 7);
    int bad_sse2 = 0, bad_avx2 = 0, entered = 0, n = 200000;
    int avx2 = tex_simd_level() >= TEX_SIMD_AVX2;
    for (int k = 0; k < n; k++) {
        struct tex_box4 b;
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 4; c++) {
                double p = box_coord(&g), q = box_coord(&g);
                int order = tex_rng_below(&g, 8); /* now and then lo > hi: an empty box */
                b.lo[a][c] = order ? fmin(p, q) : fmax(p, q);
                b.hi[a][c] = order ? fmax(p, q) : fmin(p, q);
            }
        tex_v3 o = tex_v3_make(box_coord(&g), box_coord(&g), box_coord(&g));
        tex_v3 d = random_dir(&g);
        double *dc[3] = {&d.x, &d.y, &d.z};
        for (int a = 0; a < 3; a++)
            if (!tex_rng_below(&g, 3))
                *dc[a] = tex_rng_below(&g, 2) ? 0.0 : -0.0; /* along a face */
        tex_v3 inv = tex_v3_slab_inv(d);
        double tmin = tex_rng_below(&g, 2) ? 0 : tex_rng_uniform(&g);
        double tmax = tex_rng_below(&g, 2) ? INFINITY : 4 * tex_rng_uniform(&g);
        double t[4], ts[4], ta[4];
        int in = tex_box4_hit(&b, &o, &inv, tmin, tmax, t);
        int ins = tex_box4_sse2(&b, &o, &inv, tmin, tmax, ts);
        entered += __builtin_popcount(in);
        bad_sse2 += ins != in || memcmp(ts, t, sizeof t) != 0;
        if (avx2) {
            int ina = tex_box4_avx2(&b, &o, &inv, tmin, tmax, ta);
            bad_avx2 += ina != in || memcmp(ta, t, sizeof t) != 0;
        }
    }
    CHECKF(bad_sse2 == 0 && entered > n / 4,
           "four boxes in SSE2 lanes: tex_box4_hit's bits (%d of %d differ, %d entered)",
           bad_sse2, n, entered);
    CHECKF(bad_avx2 == 0, "four boxes in AVX2 lanes: tex_box4_hit's bits (%d of %d differ%s)",
           bad_avx2, n, avx2 ? "" : "; no AVX2 here");
#endif
}

/* A packet's rays walking the tree together find each ray's own closest hit, the same object
 * at the same t (ties between twin objects included), at every SIMD level; packets of 64
 * rays from the eye through an 8 x 8 grid of neighbouring directions, and of fewer */
static void test_packet_walk(void)
{
    tex_rng g;
    tex_rng_seed(&g, 43);
    struct tex_scene *s = bvh_scene(&g, 1);
    CHECK(s != NULL, "scene of twin objects prepares");
    if (!s)
        return;
    int levels[2] = {tex_simd_level(), TEX_SIMD_SCALAR}, bad = 0, hits = 0, ties = 0, rays = 0;
    for (int lv = 0; lv < 2; lv++) {
        tex_simd_limit(levels[lv]);
        for (int p = 0; p < 300; p++) {
            tex_ray r[64];
            struct tex_hit h[64], one;
            int found[64], n = p % 5 ? 64 : 1 + (int)tex_rng_below(&g, 64);
            double x0 = 1.4 * tex_rng_uniform(&g) - 0.7, y0 = 1.4 * tex_rng_uniform(&g) - 0.7;
            double step = p % 2 ? 0.002 : 0.02;
            for (int k = 0; k < n; k++) {
                r[k] = (tex_ray){0};
                r[k].o = tex_v3_make(0, 0, -30);
                r[k].d = tex_v3_norm(tex_v3_make(x0 + step * (k % 8), y0 + step * (k / 8), 1));
            }
            ties += tex_scene_trace_packet(s, n, r, ~0ull, h, found);
            for (int k = 0; k < n; k++, rays++) {
                int f = tex_scene_trace_view(s, &r[k].o, &r[k].d, ~0ull, &one);
                hits += f;
                bad += f != found[k] || (f && (memcmp(&one.t, &h[k].t, sizeof one.t) != 0 ||
                                               one.leaf != h[k].leaf || one.flip != h[k].flip));
            }
        }
    }
    tex_simd_limit(levels[0]);
    CHECKF(bad == 0 && hits > rays / 4 && ties > 0,
           "a packet's walk finds each ray's own closest hit (%d of %d differ, %d hits, %d ties)",
           bad, rays, hits, ties);
    tex_scene_free(s);
}

/* A packet's rays against four boxes in AVX2's lanes: tex_box4_rays's rays and entries */
static void test_box4_rays_lanes(void)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2)
        return;
    tex_rng g;
    tex_rng_seed(&g, 8);
    int bad = 0, entered = 0, n = 4000;
    struct tex_ray_lanes l;
    double tmin[64], tmax[64];
    l.tmin = tmin, l.tmax = tmax;
    for (int k = 0; k < n; k++) {
        struct tex_box4 b;
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 4; c++) {
                double p = box_coord(&g), q = box_coord(&g);
                b.lo[a][c] = fmin(p, q), b.hi[a][c] = fmax(p, q);
            }
        for (int i = 0; i < 64; i++) {
            tex_v3 d = random_dir(&g);
            double *dc[3] = {&d.x, &d.y, &d.z};
            for (int a = 0; a < 3; a++)
                if (!tex_rng_below(&g, 3))
                    *dc[a] = tex_rng_below(&g, 2) ? 0.0 : -0.0; /* along a face */
            tex_v3 inv = tex_v3_slab_inv(d);
            l.o[0][i] = box_coord(&g), l.o[1][i] = box_coord(&g), l.o[2][i] = box_coord(&g);
            l.inv[0][i] = inv.x, l.inv[1][i] = inv.y, l.inv[2][i] = inv.z;
            tmin[i] = tex_rng_below(&g, 2) ? 0 : tex_rng_uniform(&g);
            tmax[i] = tex_rng_below(&g, 2) ? INFINITY : 4 * tex_rng_uniform(&g);
        }
        uint64_t m = (uint64_t)tex_rng_below(&g, 1u << 31) << 33 ^ tex_rng_below(&g, 1u << 31);
        int mask = 1 + (int)tex_rng_below(&g, 15);
        uint64_t in[4], ia[4];
        double t[4], ta[4];
        tex_box4_rays(&b, mask, &l, m, in, t);
        tex_box4_rays_avx2(&b, mask, &l, m, ia, ta);
        for (int c = 0; c < 4; c++) {
            entered += __builtin_popcountll(in[c]);
            bad += in[c] != ia[c] || !(t[c] == ta[c]) || (in[c] & ~m) || (!(mask >> c & 1) && in[c]);
        }
    }
    CHECKF(bad == 0 && entered > n * 4, "a packet's rays against four boxes in AVX2 lanes: "
           "tex_box4_rays's (%d of %d differ, %d entered)", bad, 4 * n, entered);
#endif
}

/* A point of box b (on the grid where box_coord puts its faces): one of its corners, a point
 * of one of its faces, or anywhere near */
static tex_v3 box_point(tex_rng *g, const struct tex_bounds *b)
{
    double lo[3] = {b->lo.x, b->lo.y, b->lo.z}, hi[3] = {b->hi.x, b->hi.y, b->hi.z}, p[3];
    int kind = (int)tex_rng_below(g, 3), face = (int)tex_rng_below(g, 3);
    for (int a = 0; a < 3; a++)
        p[a] = kind == 0 || (kind == 1 && a == face) ? (tex_rng_below(g, 2) ? lo[a] : hi[a])
                                                     : box_coord(g);
    return tex_v3_make(p[0], p[1], p[2]);
}

/* A direction from o grazing box b: along one or two of the axes' planes (zero components),
 * to one of its corners (ties in the slabs), or any */
static tex_v3 graze_dir(tex_rng *g, tex_v3 o, const struct tex_bounds *b)
{
    tex_v3 d = random_dir(g);
    if (tex_rng_below(g, 2)) {
        tex_v3 c = tex_v3_make(tex_rng_below(g, 2) ? b->lo.x : b->hi.x,
                               tex_rng_below(g, 2) ? b->lo.y : b->hi.y,
                               tex_rng_below(g, 2) ? b->lo.z : b->hi.z);
        if (tex_v3_dot(tex_v3_sub(c, o), tex_v3_sub(c, o)) > 0)
            d = tex_v3_sub(c, o);
    }
    double *dc[3] = {&d.x, &d.y, &d.z};
    for (int a = 0; a < 3; a++)
        if (!tex_rng_below(g, 3))
            *dc[a] = tex_rng_below(g, 2) ? 0.0 : -0.0;
    return d;
}

/* A batch of shadow rays against a box in AVX2's lanes (and AVX-512's where the CPU has
 * them) gives each ray's own slab test (tex_box4_hit's lane: hit_box's operations in its
 * order) for rays from the box's corners and faces, along its faces and to its corners */
static void test_rays_box_lanes(void)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2)
        return;
    tex_rng g;
    tex_rng_seed(&g, 9);
    int wide = tex_simd_level() >= TEX_SIMD_AVX512, n = 4000;
    long bad[2] = {0, 0}, entered = 0, asked = 0, graze = 0;
    struct tex_ray_lanes l;
    double tmin[64], tmax[64];
    l.tmin = tmin, l.tmax = tmax;
    for (int k = 0; k < n; k++) {
        double p[3], q[3];
        for (int a = 0; a < 3; a++)
            p[a] = box_coord(&g), q[a] = tex_rng_below(&g, 8) ? box_coord(&g) : p[a]; /* flat */
        struct tex_bounds b = {tex_v3_make(fmin(p[0], q[0]), fmin(p[1], q[1]), fmin(p[2], q[2])),
                               tex_v3_make(fmax(p[0], q[0]), fmax(p[1], q[1]), fmax(p[2], q[2]))};
        struct tex_box4 b4;
        for (int c = 0; c < 4; c++)
            for (int a = 0; a < 3; a++)
                b4.lo[a][c] = tex_v3_get(b.lo, a), b4.hi[a][c] = tex_v3_get(b.hi, a);
        uint64_t m = (uint64_t)tex_rng_below(&g, 1u << 31) << 33 ^ tex_rng_below(&g, 1u << 31);
        uint64_t want = 0;
        for (int i = 0; i < 64; i++) {
            tex_v3 o = box_point(&g, &b), inv = tex_v3_slab_inv(graze_dir(&g, o, &b));
            for (int a = 0; a < 3; a++)
                l.o[a][i] = tex_v3_get(o, a), l.inv[a][i] = tex_v3_get(inv, a);
            tmin[i] = tex_rng_below(&g, 2) ? 0 : tex_rng_uniform(&g);
            tmax[i] = tex_rng_below(&g, 2) ? INFINITY : 4 * tex_rng_uniform(&g);
            double t[4];
            want |= (uint64_t)(tex_box4_hit(&b4, &o, &inv, tmin[i], tmax[i], t) & 1) << i;
            for (int a = 0; a < 3; a++) /* along a face's plane: a slab of +-0 and +-inf */
                graze += (m >> i & 1) && fabs(l.inv[a][i]) > 1e299 &&
                         (l.o[a][i] == tex_v3_get(b.lo, a) || l.o[a][i] == tex_v3_get(b.hi, a));
        }
        want &= m;
        bad[0] += __builtin_popcountll(tex_rays_box_avx2(&b, &l, m) ^ want);
        if (wide)
            bad[1] += __builtin_popcountll(tex_rays_box_avx512(&b, &l, m) ^ want);
        entered += __builtin_popcountll(want), asked += __builtin_popcountll(m);
    }
    CHECKF(bad[0] == 0 && entered > asked / 8 && entered < asked - asked / 8 && graze > n,
           "shadow rays against a box in AVX2 lanes: each one's slab test (%ld of %ld differ, "
           "%ld entered, %ld along a face)", bad[0], asked, entered, graze);
    CHECKF(bad[1] == 0, "shadow rays against a box in AVX-512 lanes: each one's slab test "
           "(%ld of %ld differ%s)", bad[1], asked, wide ? "" : "; no AVX-512 here");
#endif
}

/* A random unit vector; one in eight along an axis, to give head-on views */
static tex_v3 unit_dir(tex_rng *g)
{
    if (!tex_rng_below(g, 8))
        return tex_v3_make(0, tex_rng_below(g, 2) ? 1 : -1, 0);
    tex_v3 v = tex_v3_make(2 * tex_rng_uniform(g) - 1, 2 * tex_rng_uniform(g) - 1,
                           2 * tex_rng_uniform(g) - 1);
    return tex_v3_norm(v);
}

/* Four random hits' frames for the footprint lanes: directions D (one in six head-on) at
 * normals N, the mapping's gradients gr and placement pm; shared or not, at random (shared
 * rows beyond lane 0 left NaN, as the lanes must not read them) */
static void random_frames(tex_rng *g, struct frames *fr, const tex_v3 gr[3],
                          const struct placement *pm, tex_v3 D[4], tex_v3 N[4])
{
    for (int c = 0; c < 3; c++)
        fr->d[c] = fr->rows[c], fr->nn[c] = fr->rows[3 + c];
    fr->w = fr->rows[6];
    fr->shared = (int)tex_rng_below(g, 2);
    for (int l = 0; l < 4; l++) {
        N[l] = unit_dir(g);
        D[l] = tex_rng_below(g, 6) ? unit_dir(g) : tex_v3_scale(N[l], -1);
        for (int c = 0; c < 3; c++)
            fr->rows[c][l] = tex_v3_get(D[l], c), fr->rows[3 + c][l] = tex_v3_get(N[l], c);
        fr->rows[6][l] = tex_rng_below(g, 4) ? 1e-3 * tex_rng_uniform(g) : 0.5;
        for (int c = 0; c < 3; c++) /* shared: lane 0's alone */
            fr->gu[c][l] = tex_v3_get(gr[0], c), fr->gv[c][l] = tex_v3_get(gr[1], c),
            fr->gw[c][l] = tex_v3_get(gr[2], c);
        fr->su[l] = fr->shared && l ? NAN : pm->su;
        fr->sv[l] = fr->shared && l ? NAN : pm->sv;
        if (fr->shared && l)
            fr->gu[0][l] = fr->gv[1][l] = fr->gw[2][l] = NAN;
    }
}

/* The AVX2 footprint kernels against the scalar path's own: tex_footprint_width2 and
 * tex_solid_width2 (its root) on world and solid mappings, the bump's unit tangents and
 * placed derivatives (footprint_unit, placed_derivatives), bit for bit, lanes of their own
 * or shared; the head-on lanes, left to the scalar path, as footprint_tangents finds them */
static void test_footprint_lanes(void)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2)
        return;
    static struct frames fr;
    struct tex_apply ap[2];
    struct tex_object leaf;
    struct placement pm[2] = {{1, 1, 8, 8, 1}, {1, 1, 0.25, 3, 1}};
    memset(ap, 0, sizeof ap), memset(&leaf, 0, sizeof leaf);
    ap[0].mapping = TEX_MAP_WORLD, ap[0].scale = 0.25;
    ap[1].mapping = TEX_MAP_SOLID, ap[1].scale = 1.5, ap[1].placed = 1;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            ap[1].to_tex.m[r][c] = (r == c) + 0.3 * (r + 1) * (c - 1.5);
    tex_rng g;
    tex_rng_seed(&g, 23);
    long bad = 0, bad_solid = 0, headon = 0, checked = 0;
    for (int k = 0; k < 20000; k++) {
        int n = 1 + (int)tex_rng_below(&g, 4), which = (int)tex_rng_below(&g, 2);
        tex_v3 gr[3], D[4], N[4];
        map_gradient(&ap[which], &leaf, gr);
        random_frames(&g, &fr, gr, &pm[which], D, N);
        double fw2[4] = {-1, -1, -1, -1}, fw[4] = {-1, -1, -1, -1};
        unsigned ho = tex_footprints4_avx2(&fr, 0, n, 1, fw2);
        unsigned hs = tex_solid_footprints4_avx2(&fr, 0, n, fw);
        for (int l = 0; l < 4; l++) {
            if (l >= n) { /* beyond the batch: untouched */
                bad += fw2[l] != -1, bad_solid += fw[l] != -1;
                continue;
            }
            tex_v3 t1 = tex_v3_madd(D[l], N[l], -tex_v3_dot(D[l], N[l]));
            int on = tex_v3_dot(t1, t1) < 1e-18;
            bad += on != (int)(ho >> l & 1), bad_solid += on != (int)(hs >> l & 1);
            headon += on;
            if (on)
                continue;
            checked++;
            struct footprint fp;
            tex_v3 P = tex_v3_make(0, 0, 0);
            double du[2], dv[2], want;
            footprint_at(&fp, &D[l], &N[l], fr.rows[6][l]);
            want = tex_footprint_width2(&ap[which], &pm[which], &leaf, &fp, &P, &P, 1, 0, 0);
            bad += memcmp(&want, &fw2[l], sizeof want) != 0;
            footprint_at(&fp, &D[l], &N[l], fr.rows[6][l]);
            want = sqrt(tex_solid_width2(&ap[which], &pm[which], &leaf, &fp, &P, &P,
                                         (double[3]){0, 0, 0}));
            bad_solid += memcmp(&want, &fw[l], sizeof want) != 0;
            footprint_at(&fp, &D[l], &N[l], fr.rows[6][l]);
            footprint_unit(&fp);
            placed_derivatives(&ap[which], &pm[which], &leaf, &fp, &P, 1, du, dv);
            double got[10] = {fr.e1[0][l], fr.e1[1][l], fr.e1[2][l], fr.e2[0][l], fr.e2[1][l],
                              fr.e2[2][l], fr.du[0][l], fr.du[1][l], fr.dv[0][l], fr.dv[1][l]};
            double exp[10] = {fp.t1.x, fp.t1.y, fp.t1.z, fp.t2.x, fp.t2.y, fp.t2.z,
                              du[0], du[1], dv[0], dv[1]};
            bad += memcmp(got, exp, sizeof got) != 0;
        }
    }
    CHECKF(bad == 0 && headon > 1000 && checked > 20000,
           "footprints in AVX2 lanes: tex_footprint_width2's and the bump's frame, bit for bit "
           "(%ld wrong; %ld lanes checked, %ld head-on)", bad, checked, headon);
    CHECKF(bad_solid == 0, "band-limited solids' footprints in AVX2 lanes: tex_solid_width2's "
           "root, bit for bit (%ld wrong)", bad_solid);
#endif
}

/* A coordinate for a plane's mapping: most in a few units, some on whole numbers, at -0,
 * beyond 2^52 or not finite (fract's edges) */
static double plane_coord(tex_rng *g)
{
    switch (tex_rng_below(g, 16)) {
    case 0: return (double)((int)tex_rng_below(g, 9) - 4);
    case 1: return -0.0;
    case 2: return (tex_rng_below(g, 2) ? -1 : 1) * 0x1p53 * (1 + tex_rng_uniform(g));
    case 3: return tex_rng_below(g, 2) ? INFINITY : NAN;
    default: return 16 * tex_rng_uniform(g) - 8;
    }
}

/* tex_plane_map4_avx2 against map_point_at and place, the scalar path's planar mapping of a
 * plane: the coordinates, the placed ones and the lanes inside the window, bit for bit */
static void test_plane_lanes(void)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2)
        return;
    static struct tex_lanes L;
    struct tex_apply ap;
    struct tex_object leaf;
    struct tex_surface sf;
    struct tex_surface_cache cache;
    struct placement pm;
    memset(&ap, 0, sizeof ap), memset(&leaf, 0, sizeof leaf);
    memset(&sf, 0, sizeof sf), memset(&cache, 0, sizeof cache);
    ap.mapping = TEX_MAP_PLANAR, ap.scale = 0.37, ap.nu = 3, ap.nv = 2;
    ap.u1 = 0.1, ap.u2 = 0.8, ap.v1 = 0.25, ap.v2 = 1;
    tex_placement_of(&ap, &pm);
    leaf.kind = TEX_SHAPE_PLANE;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            leaf.to_obj.m[r][c] = (r == c) + 0.2 * (c - r) + (c == 3) * 0.3 * (r + 1);
    cache.placement = &pm;
    sf.apply = &ap, sf.cache = &cache;
    L.sf = &sf, L.leaf = &leaf;
    tex_rng g;
    tex_rng_seed(&g, 29);
    long bad = 0, inside = 0, lanes = 0;
    for (int k = 0; k < 20000; k++) {
        int n = 1 + (int)tex_rng_below(&g, 4);
        double u0[4], v0[4], u[4], v[4];
        for (int l = 0; l < 4; l++)
            for (int c = 0; c < 3; c++)
                L.p[c][l] = tex_rng_below(&g, 4) ? 16 * tex_rng_uniform(&g) - 8 : plane_coord(&g);
        unsigned in = tex_plane_map4_avx2(&L, 0, n, u0, v0, u, v);
        for (int l = 0; l < n; l++, lanes++) {
            tex_v3 P = tex_v3_make(L.p[0][l], L.p[1][l], L.p[2][l]);
            tex_v3 pl = tex_xform_point(&leaf.to_obj, P);
            double uvw[3], got[2] = {u0[l], v0[l]};
            map_point_at(&ap, &leaf, &P, &pl, uvw);
            bad += memcmp(got, uvw, sizeof got) != 0;
            int want = place(&ap, &pm, uvw);
            bad += want != (int)(in >> l & 1);
            inside += want;
            if (want)
                bad += memcmp(&u[l], &uvw[0], sizeof *u) != 0 || memcmp(&v[l], &uvw[1], sizeof *v);
        }
        bad += in >> n != 0;
    }
    CHECKF(bad == 0 && inside > lanes / 8 && inside < lanes - lanes / 8,
           "a plane's planar mapping in AVX2 lanes: map_point_at's and place's bits (%ld wrong "
           "of %ld lanes, %ld inside)", bad, lanes, inside);
#endif
}

/* The eye rays in AVX2's lanes (tex_eye_rays4_avx2 through tex_camera_rays) against the
 * portable path's, bit for bit: 1 and 9 samples a pixel (jittered), packets of 1 to 64
 * pixels anywhere on the image, a camera tilted off its axes */
static void test_eye_rays_lanes(void)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2)
        return;
    long bad = 0, rays = 0;
    for (int spp = 1; spp <= 9; spp += 8) {
        char sc[200];
        int len = snprintf(sc, sizeof sc, "image 801 599 samples %d\n"
                                          "camera { eye 0.3 3 -7 look 0.1 0.8 0.2 fov 47 }\n"
                                          "sphere { radius 1 }\n", spp);
        struct tex_scene *s = tex_scene_parse(sc, len, "eye.scene");
        CHECK(s && tex_scene_prepare(s) == 0, "eye rays' scene prepares");
        if (!s)
            return;
        struct tex_camera cam;
        tex_camera_setup(s, &cam);
        tex_rng g;
        tex_rng_seed(&g, 31);
        for (int t = 0; t < 400; t++) {
            int x[64], y[64], np = 1 + (int)tex_rng_below(&g, 64), i = (int)tex_rng_below(&g, spp);
            tex_rng rng[2][64];
            tex_ray r[2][64];
            for (int k = 0; k < 64; k++) {
                x[k] = (int)tex_rng_below(&g, 801), y[k] = (int)tex_rng_below(&g, 599);
                tex_rng_seed(&rng[0][k], (uint64_t)t * 64 + k);
                rng[1][k] = rng[0][k];
            }
            tex_simd_limit(TEX_SIMD_SCALAR);
            tex_camera_rays(s, &cam, x, y, np, i, rng[0], r[0]);
            tex_simd_limit(TEX_SIMD_AVX2);
            tex_camera_rays(s, &cam, x, y, np, i, rng[1], r[1]);
            tex_simd_limit(TEX_SIMD_AVX512);
            for (int k = 0; k < np; k++, rays++)
                bad += memcmp(&r[0][k].o, &r[1][k].o, sizeof r[0][k].o) != 0 ||
                       memcmp(&r[0][k].d, &r[1][k].d, sizeof r[0][k].d) != 0 ||
                       r[0][k].spread != r[1][k].spread || r[0][k].width != r[1][k].width ||
                       r[0][k].dist != r[1][k].dist || r[0][k].media != r[1][k].media;
        }
        tex_scene_free(s);
    }
    CHECKF(bad == 0 && rays > 10000, "eye rays in AVX2 lanes: the portable path's bits (%ld of "
           "%ld differ)", bad, rays);
#endif
}

/* A point or spot light's samples at four hits in AVX2's lanes (tex_light_points4_avx2)
 * against tex_light_ahead_at's, bit for bit where they reach the hit: every falloff, spots
 * of whole exponents 0 to 9, hits at the light, across the cone's edge and far off */
static void test_light_lanes(void)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2)
        return;
    tex_rng g;
    tex_rng_seed(&g, 37);
    long bad = 0, lit = 0, dark = 0, n = 0;
    for (int t = 0; t < 6000; t++) {
        struct tex_light l;
        memset(&l, 0, sizeof l);
        l.kind = tex_rng_below(&g, 2) ? TEX_LIGHT_SPOT : TEX_LIGHT_POINT;
        l.pos = tex_v3_make(4 * tex_rng_uniform(&g) - 2, 3, 4 * tex_rng_uniform(&g) - 2);
        l.dir = tex_v3_norm(
            tex_v3_make(tex_rng_uniform(&g) - 0.5, -1, tex_rng_uniform(&g) - 0.5));
        l.falloff = (enum tex_falloff)tex_rng_below(&g, 3);
        l.c1 = tex_rng_below(&g, 2) ? 1 : 0.2, l.c2 = 0.02 * tex_rng_uniform(&g);
        l.c3 = 0.5 * tex_rng_uniform(&g);
        l.cos_angle = cos(0.7 * tex_rng_uniform(&g)), l.exponent = (int)tex_rng_below(&g, 10);
        tex_v3 P[4];
        for (int k = 0; k < 4; k++) {
            double sc = tex_rng_below(&g, 8) ? 4 : 1e6;
            P[k] = tex_rng_below(&g, 16) ? tex_v3_make(sc * (tex_rng_uniform(&g) - 0.5),
                                                       sc * (tex_rng_uniform(&g) - 0.5),
                                                       sc * (tex_rng_uniform(&g) - 0.5))
                                         : l.pos; /* at the light */
        }
        if (!tex_light_lanes(&l))
            continue;
        struct tex_light_ahead a[4], w;
        tex_light_points4_avx2(&l, P, a);
        for (int k = 0; k < 4; k++, n++) {
            tex_light_ahead_at(&l, 0, 0.5, 0.5, &P[k], &w);
            bad += a[k].ok != w.ok;
            if (w.ok)
                bad += memcmp(&a[k].L, &w.L, sizeof w.L) != 0 ||
                       memcmp(&a[k].dist, &w.dist, sizeof w.dist) != 0 ||
                       memcmp(&a[k].fatt, &w.fatt, sizeof w.fatt) != 0;
            lit += w.ok, dark += !w.ok;
        }
    }
    CHECKF(bad == 0 && lit > n / 8 && dark > n / 8, "point and spot lights at four hits in AVX2 "
           "lanes: tex_light_ahead_at's bits (%ld of %ld differ, %ld lit)", bad, n, lit);
#endif
}

/* A batch of shadow rays through a tree of glass and opaque boxes on a grid (from their
 * corners and faces, along their faces, to their corners) gives each ray's own product of
 * Kt, bit for bit, at every SIMD level; so do batches from one origin */
static void test_transmit_batch(void)
{
    tex_rng g;
    tex_rng_seed(&g, 11);
    size_t cap = 40000, len = 0;
    char *sc = malloc(cap);
    struct tex_bounds bx[80];
    len += snprintf(sc, cap, "image 8 8\nsurface a { Kd 0.2 Kt 0.5 }\nsurface b { Kd 0.2 Kt 0.9 }\n"
                             "surface c { Kd 0.2 }\n");
    for (int i = 0; i < 80; i++) {
        double x = 0.5 * ((int)tex_rng_below(&g, 16) - 8);
        double y = 0.5 * ((int)tex_rng_below(&g, 16) - 8);
        double z = 0.5 * ((int)tex_rng_below(&g, 16) - 8);
        bx[i].lo = tex_v3_make(x, y, z);
        bx[i].hi = tex_v3_make(x + 0.5 * (1 + (int)tex_rng_below(&g, 3)),
                               y + 0.5 * (1 + (int)tex_rng_below(&g, 3)),
                               z + 0.5 * (1 + (int)tex_rng_below(&g, 3)));
        len += snprintf(sc + len, cap - len, "box { min %g %g %g max %g %g %g surface %c }\n", x,
                        y, z, bx[i].hi.x, bx[i].hi.y, bx[i].hi.z, "abc"[i % 3]);
    }
    struct tex_scene *s = tex_scene_parse(sc, len, "glass.scene");
    free(sc);
    CHECK(s && tex_scene_prepare(s) == 0 && tex_scene_shadow_batches(s), "glass boxes prepare");
    if (!s)
        return;
    int levels[3] = {tex_simd_level(), TEX_SIMD_AVX2, TEX_SIMD_SCALAR}, bad = 0, rays = 0;
    int dim = 0, dark = 0;
    for (int lv = 0; lv < 3; lv++) {
        tex_simd_limit(levels[lv]);
        tex_rng_seed(&g, 12);
        for (int p = 0; p < 400; p++) {
            static struct tex_shadow_rays b;
            tex_v3 o[64], d[64];
            int n = b.n = p % 4 ? 64 : 1 + (int)tex_rng_below(&g, 64);
            /* as an area light's samples from one hit: one origin, segments to points of
             * one box, some of no length (unlit: out of the walk, the box not grown by them) */
            int share = p % 5 == 2;
            const struct tex_bounds *lamp = &bx[tex_rng_below(&g, 80)];
            for (int i = 0; i < n; i++) {
                const struct tex_bounds *a = &bx[tex_rng_below(&g, 80)];
                o[i] = b.r[i].o = share && i ? o[0] : box_point(&g, a);
                d[i] = b.r[i].d = graze_dir(&g, o[i], &bx[tex_rng_below(&g, 80)]);
                if (share)
                    d[i] = b.r[i].d = tex_rng_below(&g, 4) ? tex_v3_sub(box_point(&g, lamp), o[i])
                                                           : tex_v3_make(0, 0, 0);
                b.tmin[i] = tex_rng_below(&g, 2) ? 0 : 1e-6;
                b.tmax[i] = tex_rng_below(&g, 4) ? 1 + 8 * tex_rng_uniform(&g) : INFINITY;
                if (share)
                    b.tmax[i] = 1;
                b.from[i] = NULL;
            }
            tex_scene_transmit_n(s, &b);
            for (int i = 0; i < n; i++, rays++) {
                double one = tex_scene_transmit(s, &o[i], &d[i], b.tmin[i], b.tmax[i], NULL);
                bad += memcmp(&one, &b.tr[i], sizeof one) != 0;
                dim += one > 0 && one < 1, dark += one == 0;
            }
        }
    }
    tex_simd_limit(levels[0]);
    CHECKF(bad == 0 && dim > rays / 4 && dark > rays / 20,
           "a batch of shadow rays through glass boxes: each ray's own product of Kt at every "
           "SIMD level (%d of %d differ, %d dimmed, %d dark)", bad, rays, dim, dark);
    tex_scene_free(s);
}

/* The outward world normal at a hit on leaf h->leaf (render.c's hit_normal, unhurried). */
static tex_v3 outward_normal(const struct tex_hit *h, tex_v3 P)
{
    const struct tex_object *l = h->leaf;
    tex_v3 n = tex_shape_methods[l->kind].normal(l, tex_xform_point(&l->to_obj, P));
    n = tex_v3_norm(tex_xform_normal(&l->to_obj, n));
    return h->flip ? tex_v3_scale(n, -1) : n;
}

/* The hull leaves of ob (struct tex_object's hull): *in counts them, *out the others. */
static void count_hulls(const struct tex_object *ob, int *in, int *out)
{
    if (ob->op != TEX_CSG_LEAF) {
        count_hulls(ob->a, in, out);
        count_hulls(ob->b, in, out);
    } else {
        *(ob->hull ? in : out) += 1;
    }
}

/* Rays leaving a hull leaf outwards skip its object: the answers with and without that
 * object named must agree, and the other leaves' rays must still meet their objects. */
static void test_hull_skip(void)
{
    static const struct {
        const char *ob;
        int in, out; /* hull leaves and others */
    } obs[] = {
        {"sphere { radius 1 scale 1 0.5 2 rotate 0 40 0 translate %g %g %g }", 1, 0},
        {"box { min -1 -1 -1 max 1 2 1 rotate 5 15 25 translate %g %g %g }", 1, 0},
        {"cone { base 0 0 0 top 0 2 0 radius1 1 radius2 0 translate %g %g %g }", 1, 0},
        {"intersection { sphere { radius 1.2 } box { min -1 -1 -1 max 1 1 1 } "
         "translate %g %g %g }", 2, 0},
        {"difference { box { min -1 -1 -1 max 1 1 1 } sphere { radius 1.3 } "
         "translate %g %g %g }", 1, 1},
        {"union { sphere { radius 1 } sphere { centre 1.5 0 0 radius 1 } translate %g %g %g }",
         0, 2},
        {"torus { major 1 minor 0.3 rotate 60 0 0 translate %g %g %g }", 0, 1},
        {"intersection { torus { major 1 minor 0.4 } box { min -2 -0.2 -2 max 2 2 2 } "
         "translate %g %g %g }", 1, 1},
    };
    enum { N = sizeof obs / sizeof *obs };
    char sc[4096];
    int len = snprintf(sc, sizeof sc, "image 8 8\nplane { }\n");
    for (int i = 0; i < N; i++) {
        len += snprintf(sc + len, sizeof sc - len, obs[i].ob, 4.0 * (i % 4) - 6, 1.5,
                        5.0 * (i / 4));
        len += snprintf(sc + len, sizeof sc - len, "\n");
    }
    struct tex_scene *s = tex_scene_parse(sc, len, "hull.scene");
    CHECK(s && tex_scene_prepare(s) == 0 && s->nobjects == N + 1, "hull scene prepares");
    if (!s || s->nobjects != N + 1)
        return;
    int right = s->objects[0]->hull;
    for (int i = 0; i < N; i++) {
        int in = 0, out = 0;
        count_hulls(s->objects[i + 1], &in, &out);
        right += in == obs[i].in && out == obs[i].out;
    }
    CHECKF(right == N + 1, "hull leaves: convex, inside every node above (%d of %d right)",
           right, N + 1);
    tex_rng g;
    tex_rng_seed(&g, 24);
    int differ = 0, leaving = 0, self[2] = {0, 0}; /* self-hits from hull leaves, others */
    for (int k = 0; k < 20000; k++) {
        const struct tex_object *ob = s->objects[1 + k % N];
        tex_v3 c = tex_v3_scale(tex_v3_add(ob->wb.lo, ob->wb.hi), 0.5);
        tex_v3 d = random_dir(&g);
        tex_v3 o = tex_v3_madd(c, d, -8), aim = tex_v3_make(tex_rng_uniform(&g) - 0.5,
                                                           tex_rng_uniform(&g) - 0.5, 0);
        d = tex_v3_norm(tex_v3_sub(tex_v3_add(c, aim), o));
        struct tex_hit h, a, b;
        if (!tex_scene_trace(s, &o, &d, 0, INFINITY, NULL, &h))
            continue;
        const struct tex_object *top = tex_object_top(h.leaf);
        tex_v3 P = tex_v3_madd(o, d, h.t), Ng = outward_normal(&h, P);
        tex_v3 r = random_dir(&g);
        if (!(tex_v3_dot(d, Ng) < 0) || fabs(tex_v3_dot(r, Ng)) < 0.05)
            continue;
        if (tex_v3_dot(r, Ng) < 0)
            r = tex_v3_sub(r, tex_v3_scale(Ng, 2 * tex_v3_dot(r, Ng))); /* away from it */
        double e = 1e-6 * (1 + fmax(fabs(P.x), fmax(fabs(P.y), fabs(P.z))));
        tex_v3 Pout = tex_v3_madd(P, Ng, e);
        const struct tex_object *from = h.leaf->hull ? top : NULL;
        leaving += from != NULL;
        int fa = tex_scene_trace(s, &Pout, &r, 0, INFINITY, NULL, &a);
        int fb = tex_scene_trace(s, &Pout, &r, 0, INFINITY, from, &b);
        double ta = tex_scene_transmit(s, &Pout, &r, 0, 30, NULL);
        double tb = tex_scene_transmit(s, &Pout, &r, 0, 30, from);
        differ += fa != fb || (fa && (a.t != b.t || a.leaf != b.leaf)) || ta != tb;
        if (fa && tex_object_top(a.leaf) == top)
            self[from ? 0 : 1]++;
    }
    CHECKF(differ == 0 && leaving > 5000 && self[0] == 0 && self[1] > 100,
           "rays leaving a hull leaf skip its object unchanged (%d of %d differ; self-hits: %d "
           "from hull leaves, %d from others)", differ, leaving, self[0], self[1]);
    tex_scene_free(s);
}

/* Leaves placed by scales and shifts alone take their spans without the transform's zero
 * terms (tex_object's scaled): the same spans as the full products, to the last bit but a
 * zero's sign. */
static void test_scaled_leaves(void)
{
    const char *sc = "image 8 8\n"
                     "box { min -1 0.5 -2 max 1.5 2 3 }\n"
                     "sphere { centre 0.5 -1 2 radius 0.7 }\n"
                     "sphere { radius 1 scale 2 0.5 1 translate 1 1 1 }\n"
                     "cylinder { base 1 0 1 top 1 3 1 radius 0.4 }\n"
                     "cone { base -1 -1 0 top -1 1 0 radius1 0.8 radius2 0.2 }\n"
                     "torus { major 1 minor 0.25 translate 0 0.3 0 }\n"
                     "box { min 0 0 0 max 1 1 1 rotate 0 30 0 }\n";
    struct tex_scene *s = tex_scene_parse(sc, strlen(sc), "scaled.scene");
    CHECK(s && tex_scene_prepare(s) == 0, "scaled-leaf scene prepares");
    if (!s)
        return;
    int scaled = 0, differ = 0, spans = 0;
    tex_rng g;
    tex_rng_seed(&g, 7);
    for (int i = 0; i < s->nobjects; i++) {
        struct tex_object *ob = s->objects[i];
        scaled += ob->scaled;
        for (int k = 0; k < 2000; k++) {
            tex_v3 o = tex_v3_make(8 * tex_rng_uniform(&g) - 4, 8 * tex_rng_uniform(&g) - 4,
                                   8 * tex_rng_uniform(&g) - 4);
            tex_v3 d = random_dir(&g);
            if (k % 10 == 0) /* along an axis, and from the origin: zero terms */
                d = tex_v3_make(0, k % 20 ? 1 : -1, 0), o.x = 0;
            struct tex_spans a, b;
            int was = ob->scaled;
            tex_leaf_spans(ob, &o, &d, &a);
            ob->scaled = 0;
            tex_leaf_spans(ob, &o, &d, &b);
            ob->scaled = was;
            spans += a.n;
            differ += a.n != b.n;
            for (int j = 0; j < a.n && j < b.n; j++)
                differ += a.in[j].t != b.in[j].t || a.out[j].t != b.out[j].t ||
                          a.in[j].leaf != b.in[j].leaf || a.out[j].leaf != b.out[j].leaf;
        }
    }
    CHECKF(scaled == 6 && differ == 0 && spans > 1000,
           "scaled leaves' spans are the full transform's (%d of 7 scaled, %d differ of %d)",
           scaled, differ, spans);
    tex_scene_free(s);
}

/* Adaptive depth control: a bailout below every path weight changes nothing,
 * one above the deeper weights drops only their (non-negative) light. */
static void test_bailout(void)
{
    char sc[600];
    const char *fmt = "image 48 36 depth 5 bailout %g ambient 0.2 0.2 0.2 background 0.3 0.4 0.5\n"
                      "camera { eye 0 1.5 -5 look 0 0.8 0 fov 50 }\n"
                      "light point { position 3 6 -4 }\n"
                      "surface m { Ka 0.5 Kd 0.6 0.5 0.4 Ks 0.5 n 20 Kr 0.5 }\n"
                      "plane { surface m }\n"
                      "sphere { centre 0 1 0 radius 1 surface m }\n";
    double b[3] = {0, 1e-3, 0.2}, sum[3] = {0, 0, 0}, dmax[3] = {0, 0, 0};
    tex_map *m[3];
    for (int i = 0; i < 3; i++) {
        snprintf(sc, sizeof sc, fmt, b[i]);
        m[i] = unit_render_text(sc, 1);
    }
    CHECK(m[0] && m[1] && m[2], "bailout scenes render");
    if (m[0] && m[1] && m[2]) {
        size_t n = (size_t)m[0]->w * m[0]->h * 3;
        for (int i = 0; i < 3; i++)
            for (size_t k = 0; k < n; k++) {
                sum[i] += m[i]->px[k];
                double d = fabs(m[i]->px[k] - m[0]->px[k]);
                dmax[i] = d > dmax[i] ? d : dmax[i];
            }
        CHECKF(dmax[1] == 0, "bailout below every path weight (0.5^5) changes nothing (%g)",
               dmax[1]);
        CHECKF(dmax[2] > 0 && sum[2] < sum[0],
               "bailout 0.2 drops the deeper reflections (max change %g, total %g < %g)",
               dmax[2], sum[2], sum[0]);
    }
    for (int i = 0; i < 3; i++)
        tex_map_free(m[i]);
    struct tex_scene *s = tex_scene_parse("bailout 2\n", 10, "b.scene");
    CHECK(!s, "bailout outside 0..1 is refused");
    tex_scene_free(s);
    /* a scene's sample size for textures without one: its limit, and its effect */
    static const char so[] = "texture c checker { nu 2 nv 2 }\nsphere { }\n";
    s = tex_scene_parse_opts(so, sizeof so - 1, "o.scene", &(struct tex_scene_opts){0});
    CHECKF(!s && strstr(tex_errmsg(), "sample size 0: valid range 1..16384"),
           "sample size 0 is refused (%s)", tex_errmsg());
    tex_scene_free(s);
    s = tex_scene_parse_opts(so, sizeof so - 1, "o.scene", &(struct tex_scene_opts){16});
    CHECKF(s && s->ntextures == 1 && s->textures[0]->mip && s->textures[0]->mip[0]->w == 16,
           "textures without a size are sampled at the given size (%s)", s ? "" : tex_errmsg());
    tex_scene_free(s);
}

/* CSG on interval lists: every combination of two intervals (the fast path
 * for convex leaves, ties included) against membership point by point. */
static void test_csg_combine(void)
{
    static const struct tex_object la, lb; /* leaf tags */
    const double ends[] = {-INFINITY, 0, 1, 2, 3, INFINITY};
    int bad = 0, cases = 0;
    for (int op = TEX_CSG_UNION; op <= TEX_CSG_DIFFERENCE; op++)
        for (int i0 = 0; i0 < 6; i0++)
            for (int i1 = i0 + 1; i1 < 6; i1++)
                for (int j0 = 0; j0 < 6; j0++)
                    for (int j1 = j0 + 1; j1 < 6; j1++)
                        for (int bn = 0; bn < 2; bn++) {
                            struct tex_spans a, b, r;
                            a.n = 1;
                            b.n = bn;
                            a.in[0] = (struct tex_hit){ends[i0], &la, 0};
                            a.out[0] = (struct tex_hit){ends[i1], &la, 0};
                            b.in[0] = (struct tex_hit){ends[j0], &lb, 0};
                            b.out[0] = (struct tex_hit){ends[j1], &lb, 0};
                            tex_csg_combine(op, &a, &b, &r);
                            cases++;
                            for (double t = -0.75; t < 4; t += 0.5) {
                                int ia = t > ends[i0] && t < ends[i1];
                                int ib = bn && t > ends[j0] && t < ends[j1];
                                int want = op == TEX_CSG_UNION          ? ia || ib
                                           : op == TEX_CSG_INTERSECTION ? ia && ib
                                                                        : ia && !ib;
                                int got = 0;
                                for (int k = 0; k < r.n; k++)
                                    got |= t > r.in[k].t && t < r.out[k].t;
                                bad += got != want;
                            }
                            /* boundaries of the subtracted solid face the other way */
                            for (int k = 0; k < r.n; k++)
                                for (int e = 0; e < 2; e++) {
                                    const struct tex_hit *h = e ? &r.out[k] : &r.in[k];
                                    int want = op == TEX_CSG_DIFFERENCE && h->leaf == &lb;
                                    bad += h->leaf && h->flip != want;
                                }
                        }
    CHECKF(bad == 0, "CSG of two intervals matches membership (%d errors in %d cases)", bad,
           cases);
}

/* A zero Ks skips the highlight only where adding its zeros changes nothing: the bits of
 * the diffuse term plus Ks E w, with -0 in the sum so far, infinite and NaN light, -0 Ks.
 * This view, light and exponent pass the highlight's cut-off (a Ks of 0.3 adds to the
 * diffuse term), so the full model adds Ks E w there, and w's finite, positive value does
 * not change zeros. */
/* An area light's samples as tex_light_sample made them before it took a mask, a shift and
 * products by 2^-e for a power of two n: the divisions by n and n^2 */
static int area_sample_ref(const struct tex_light *l, int k, double jx, double jy, tex_v3 P,
                           tex_v3 *L, double *dist, double *fatt)
{
    int n = l->samples;
    double a = ((k % n) + jx) / n, b = ((k / n) + jy) / n, f;
    tex_v3 pos =
        tex_v3_add(l->pos, tex_v3_add(tex_v3_scale(l->edge1, a), tex_v3_scale(l->edge2, b)));
    if (!tex_light_point_at(l, &pos, &P, L, dist, &f))
        return 0;
    f /= n * n;
    *fatt = f;
    return f > 0;
}

/* Every sample of area lights of 1 to 33 samples a side, jittered, from points near and far,
 * with and without falloff: the same bits as the divisions give */
static void test_area_samples(void)
{
    tex_rng rng;
    tex_rng_seed(&rng, 63);
    long checked = 0, wrong = 0;
    for (int n = 1; n <= 33; n++)
        for (int fall = 0; fall < 2; fall++) {
            struct tex_light l = {0};
            l.kind = TEX_LIGHT_AREA;
            l.samples = n;
            l.falloff = fall ? TEX_FALL_POLY : TEX_FALL_NONE;
            l.c1 = 1, l.c2 = 0.02, l.c3 = 0.002;
            l.pos = tex_v3_make(-1.3, 6.1, -2.7);
            l.edge1 = tex_v3_make(2.3, 0.1, 0), l.edge2 = tex_v3_make(0, 0.2, 1.9);
            for (int k = 0; k < n * n; k++)
                for (int t = 0; t < 4; t++) {
                    double jx = tex_rng_uniform(&rng), jy = tex_rng_uniform(&rng);
                    double sc = t ? 1e-3 * pow(10, 2 * t) : 0;
                    tex_v3 P = tex_v3_make(sc * (jx - 0.5), sc * (jy - 0.3), sc * 0.7);
                    tex_v3 L0, L1;
                    double d0, d1, f0 = -1, f1 = -1;
                    int r0 = area_sample_ref(&l, k, jx, jy, P, &L0, &d0, &f0);
                    int r1 = tex_light_sample(&l, k, jx, jy, P, &L1, &d1, &f1);
                    checked++;
                    wrong += r0 != r1 || memcmp(&f0, &f1, sizeof f0) ||
                             (r0 && (memcmp(&L0, &L1, sizeof L0) || memcmp(&d0, &d1, sizeof d0)));
                }
        }
    CHECKF(wrong == 0, "area light samples as the divisions give: %ld of %ld differ", wrong,
           checked);
}

static void test_phong_zero_ks(void)
{
    const double N[3] = {0, 1, 0}, V[3] = {0, 0.6, -0.8}, L[3] = {0, 0.8, 0.6}, nl = 0.8;
    const float kds[3] = {0.5f, -0.0f, 0}, kss[2] = {0, -0.0f};
    const float es[4] = {1, INFINITY, NAN, 0}, outs[3] = {0, -0.0f, 0.25f};
    struct tex_material lit = {.n = 20};
    tex_colour E, diffuse, shiny;
    tex_colour_set(&lit.kd, 3, 0.5f);
    tex_colour_set(&E, 3, 1);
    tex_colour_set(&diffuse, 3, 0);
    shiny = diffuse;
    tex_phong_direct(&lit, N, V, L, &E, 3, &diffuse);
    tex_colour_set(&lit.ks, 3, 0.3f);
    tex_phong_direct(&lit, N, V, L, &E, 3, &shiny);
    CHECK(shiny.v[0] > diffuse.v[0], "the test's highlight passes the cut-off");
    int bad = 0, cases = 0, bad_dull = 0, cases_dull = 0;
    for (int n = 3; n <= 8; n += 5)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 2; b++)
                for (int e = 0; e < 4; e++)
                    for (int o = 0; o < 3; o++) {
                        struct tex_material m = {.n = 20};
                        tex_colour got, want, dull;
                        tex_colour_set(&m.kd, n, kds[a]);
                        tex_colour_set(&m.ks, n, kss[b]);
                        tex_colour_set(&E, n, 1);
                        E.v[n - 1] = es[e]; /* one sample off */
                        tex_colour_set(&got, n, outs[o]);
                        want = dull = got;
                        tex_phong_direct(&m, N, V, L, &E, n, &got);
                        tex_colour_mmadd(&want, n, &m.kd, &E, (float)nl);
                        tex_colour_mmadd(&want, n, &m.ks, &E, 1.0f);
                        bad += memcmp(got.v, want.v, n * sizeof *got.v) != 0;
                        cases++;
                        if (signbit(outs[o])) /* tex_phong_direct_dull's promise: no -0 */
                            continue;
                        tex_phong_direct_dull(&m, N, V, L, &E, n, 1, &dull);
                        bad_dull += memcmp(dull.v, want.v, n * sizeof *dull.v) != 0;
                        cases_dull++;
                    }
    CHECKF(bad == 0, "Phong with a zero Ks: the full highlight's bits (%d of %d differ)", bad,
           cases);
    CHECKF(bad_dull == 0, "Phong without highlights, tested once a hit: the same bits (%d of %d "
           "differ)", bad_dull, cases_dull);
}

/* A hit whose sum starts at -0 (Ka Kd, Kd -0) and stays there through the diffuse terms:
 * the first highlight of Ks 0 makes it +0, as tex_phong_direct has it, so direct_light
 * may not take the surface as one without highlights */
static void test_dull_negative_zero(void)
{
    const char *sc = "image 8 8\nambient 1 1 1\n"
                     "light area { position -0.5 4 -0.5 edge1 1 0 0 edge2 0 0 1 samples 4 }\n"
                     "surface s { Ka 0.5 Kd -0 Ks 0 }\nplane { surface s }\n";
    struct tex_scene *s = tex_scene_parse(sc, strlen(sc), "zero.scene");
    CHECK(s && tex_scene_prepare(s) == 0, "the -0 scene prepares");
    if (!s)
        return;
    tex_colour ambient, background, out;
    s->cs.from_rgb(&s->cs, s->ambient, TEX_SPECTRUM_ILLUMINANT, &ambient);
    s->cs.from_rgb(&s->cs, s->background, TEX_SPECTRUM_ILLUMINANT, &background);
    tex_rng g;
    tex_rng_seed(&g, 5);
    struct tex_render_ctx c = {s, s->cs.n, &ambient, &background, &g, 1, 0, 0};
    tex_ray r = {tex_v3_make(0, 2, 0), tex_v3_make(0, -1, 0), 0, 0, NULL, 0};
    tex_trace(&c, &r, NULL, 0, 1, &out);
    int neg = 0;
    for (int i = 0; i < c.n; i++)
        neg += out.v[i] != 0 || signbit(out.v[i]);
    CHECKF(neg == 0, "a sum at -0, a highlight of Ks 0 added: +0 (%d of %d samples not)", neg,
           c.n);
    tex_scene_free(s);
}

/* A plain surface's Kd expressions left by tex_plain_resolve and run over many hits together
 * (tex_plain_later_run): Ka and Kd bit for bit those of each hit's own run (tex_appfn_eval,
 * clamped as apply_fn clamps, times Ka as material scales it), hits of several functions
 * mixed, palettes' positions at their ends, outside them and not finite */
static void test_later_run(void)
{
    const char *sc = "image 8 8\ntexture t turbulence { solid }\n"
                     "surface s0 { Ks 0.5 apply t { mapping solid Kd = palette(marble, 0.5 + 0.5 "
                     "* sin(6 * ox + 12 * f)) } }\n"
                     "surface s1 { apply t { mapping solid Kd = palette(wood, f) } }\n"
                     "surface s2 { apply t { mapping solid Kd = palette(fire, min(f, p) / 0.7 "
                     "- nz) } }\n"
                     "surface s3 { apply t { mapping solid Kd = rgb(abs(f - 0.3), -p, f * p) * "
                     "2 } }\n"
                     "surface s4 { apply t { mapping solid Kd = palette(wood, mix(f, p, 0.25)) "
                     "+ max(f, u) } }\n"
                     "sphere { surface s0 }\n sphere { surface s1 }\n sphere { surface s2 }\n"
                     "sphere { surface s3 }\n sphere { surface s4 }\n";
    char pals[4096];
    unit_top_path("palettes", pals, sizeof pals);
    setenv("TEXTURA_PALETTES", pals, 1);
    struct tex_scene *s = tex_scene_parse(sc, strlen(sc), "later.scene");
    CHECKF(s && tex_scene_prepare(s) == 0, "palette expressions' scene prepares (%s)",
           s ? "" : tex_errmsg());
    if (!s)
        return;
    enum { FNS = 5, HITS = 150 };
    const struct tex_appfn *fns[FNS];
    int nf = 0;
    for (int i = 0; i < s->nsurfaces && nf < FNS; i++)
        if (s->surfaces[i]->apply && s->surfaces[i]->cache->later >= 0)
            fns[nf++] = s->surfaces[i]->apply->fns;
    CHECKF(nf == FNS, "every surface's Kd function is left to run later (%d of %d)", nf, FNS);
    const float odd[] = {0, -0.0f, 1, 0.5f, -3, 7, INFINITY, -INFINITY, NAN, 1e-30f};
    tex_rng g;
    tex_rng_seed(&g, 63);
    static struct tex_plain_later later[HITS];
    static struct tex_plain m[HITS];
    long bad = 0, runs = 0;
    for (int round = 0; round < 40 && nf; round++) {
        for (int i = 0; i < HITS; i++) {
            struct tex_plain_later *l = &later[i];
            memset(l, 0, sizeof *l);
            l->fn = tex_rng_uniform(&g) < 0.1 ? NULL : fns[tex_rng_below(&g, nf)];
            int grey = tex_rng_uniform(&g) < 0.5, edge = tex_rng_uniform(&g) < 0.15;
            for (int k = 0; k < 3; k++) {
                l->f[k] = grey && k ? l->f[0]
                          : edge    ? odd[tex_rng_below(&g, 10)]
                                    : (float)(1.4 * tex_rng_uniform(&g) - 0.2);
                l->p[k] = (float)tex_rng_uniform(&g);
                l->uvw[k] = tex_rng_uniform(&g);
            }
            l->ka = (float)tex_rng_uniform(&g), l->fw2 = 1e-4 * tex_rng_uniform(&g);
            l->has_q = 1;
            for (int q = 0; q < TEX_Q_COUNT; q++)
                l->q[q] = 4 * tex_rng_uniform(&g) - 2;
            for (int k = 0; k < 3; k++)
                m[i].ka[k] = m[i].kd[k] = -7;
        }
        tex_plain_later_run(later, m, HITS);
        for (int i = 0; i < HITS; i++) {
            const struct tex_plain_later *l = &later[i];
            float ka[3] = {-7, -7, -7}, kd[3] = {-7, -7, -7};
            if (l->fn) {
                double r[3];
                tex_appfn_eval(l->fn->e, l->f, l->p, l->uvw, l->fw2, l->q, r);
                for (int k = 0; k < 3; k++) {
                    kd[k] = (float)(!(r[k] >= l->fn->lo) ? l->fn->lo
                                    : r[k] > l->fn->hi   ? l->fn->hi
                                                         : r[k]);
                    ka[k] = l->ka * kd[k];
                }
            }
            bad += memcmp(ka, m[i].ka, sizeof ka) != 0 || memcmp(kd, m[i].kd, sizeof kd) != 0;
            runs++;
        }
    }
    CHECKF(bad == 0, "Kd expressions run over hits together: each hit's own bits (%ld of %ld "
           "differ)", bad, runs);
    tex_scene_free(s);
}

int main(void)
{
    if (!mkdtemp(dir))
        return 1;
    test_silhouette();
    test_lambert();
    test_shadow();
    test_snell();
    test_difference();
    test_sphere_map();
    test_kd_f();
    test_determinism();
    test_receding();
    test_bvh_brute();
    test_box4_lanes();
    test_box4_rays_lanes();
    test_rays_box_lanes();
    test_footprint_lanes();
    test_plane_lanes();
    test_eye_rays_lanes();
    test_light_lanes();
    test_transmit_batch();
    test_packet_walk();
    test_hull_skip();
    test_scaled_leaves();
    test_bailout();
    test_csg_combine();
    test_phong_zero_ks();
    test_dull_negative_zero();
    test_later_run();
    test_area_samples();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        printf("# could not remove %s\n", dir);
    return unit_done();
}
