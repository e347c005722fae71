/* test_render_torus.c - the torus: intervals, grazing rays, silhouette, CSG */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "render/scene.h"
#include "base/rng.h"
#include "fixtures.h"
#include "unit.h"

static struct tex_object torus(double R, double r)
{
    struct tex_object ob = {0};
    ob.op = TEX_CSG_LEAF;
    ob.kind = TEX_SHAPE_TORUS;
    ob.r0 = R;
    ob.r1 = r;
    tex_xform_identity(&ob.to_world);
    tex_xform_identity(&ob.to_obj);
    return ob;
}

static int inside(double R, double r, tex_v3 p)
{
    double q = sqrt(p.x * p.x + p.z * p.z) - R;
    return q * q + p.y * p.y < r * r;
}

/* A ray across the centre plane meets the tube at +-(R - r) and +-(R + r);
 * one along the axis passes through the hole. */
static void test_crossings(void)
{
    double R = 2, r = 0.5;
    struct tex_object ob = torus(R, r);
    struct tex_spans s;
    tex_object_spans(&ob, tex_v3_make(-10, 0, 0), tex_v3_make(1, 0, 0), &s);
    double want[4] = {10 - R - r, 10 - R + r, 10 + R - r, 10 + R + r}, err = 0;
    if (s.n == 2)
        err = fmax(fmax(fabs(s.in[0].t - want[0]), fabs(s.out[0].t - want[1])),
                   fmax(fabs(s.in[1].t - want[2]), fabs(s.out[1].t - want[3])));
    CHECKF(s.n == 2 && err < 1e-12, "centre-plane ray: 2 intervals at R+-r (%d, error %g)", s.n,
           err);
    tex_object_spans(&ob, tex_v3_make(0, 10, 0), tex_v3_make(0, -1, 0), &s);
    CHECKF(s.n == 0, "ray along the axis through the hole meets nothing (%d)", s.n);
    /* a ray parameter keeps its meaning when d is not unit length */
    tex_object_spans(&ob, tex_v3_make(-10, 0, 0), tex_v3_make(4, 0, 0), &s);
    CHECKF(s.n == 2 && fabs(s.in[0].t - want[0] / 4) < 1e-12 &&
               fabs(s.out[1].t - want[3] / 4) < 1e-12,
           "unnormalised direction: t scaled (%d)", s.n);
    /* spindle torus (r > R): one solid, the quartic's inner sheet is not a surface */
    ob = torus(0.5, 1);
    tex_object_spans(&ob, tex_v3_make(0, 5, 0), tex_v3_make(0, -1, 0), &s);
    double h = sqrt(1 - 0.25);
    CHECKF(s.n == 1 && fabs(s.in[0].t - (5 - h)) < 1e-9 && fabs(s.out[0].t - (5 + h)) < 1e-9,
           "spindle torus along its axis: one interval of half length sqrt(r^2-R^2) (%d)", s.n);
    /* R = 0 is a sphere of radius r: the quartic has only double roots */
    ob = torus(0, 1);
    tex_object_spans(&ob, tex_v3_make(0.3, 0.2, -5), tex_v3_make(0, 0, 1), &s);
    h = sqrt(1 - 0.13);
    CHECKF(s.n == 1 && fabs(s.in[0].t - (5 - h)) < 1e-7 && fabs(s.out[0].t - (5 + h)) < 1e-7,
           "major radius 0 is a sphere (%d, %.9f %.9f)", s.n, s.n ? s.in[0].t : 0,
           s.n ? s.out[0].t : 0);
}

/* Rays skimming the top of the tube at height r - e: the exact crossings are
 * +-R +- sqrt(r^2 - y^2), double roots in the limit. */
static void test_grazing(void)
{
    double R = 1.5, r = 0.5;
    struct tex_object ob = torus(R, r);
    struct tex_spans s;
    double worst = 0;
    int bad = 0;
    for (int k = 1; k <= 12; k++) {
        double e = pow(10, -k), y = r - e, w = sqrt(r * r - y * y);
        tex_object_spans(&ob, tex_v3_make(-4, y, 0), tex_v3_make(1, 0, 0), &s);
        if (s.n != 2) {
            bad++;
            continue;
        }
        double want[4] = {4 - R - w, 4 - R + w, 4 + R - w, 4 + R + w};
        double got[4] = {s.in[0].t, s.out[0].t, s.in[1].t, s.out[1].t};
        for (int i = 0; i < 4; i++)
            worst = fmax(worst, fabs(got[i] - want[i]));
    }
    CHECKF(!bad && worst < 1e-7,
           "grazing rays r - 1e-1..1e-12 under the top: 4 crossings (missed %d, worst %g)", bad,
           worst);
    bad = 0;
    for (int k = 1; k <= 12; k++) {
        tex_object_spans(&ob, tex_v3_make(-4, r + pow(10, -k), 0), tex_v3_make(1, 0, 0), &s);
        bad += s.n != 0;
    }
    CHECKF(!bad, "rays just above the top miss (%d hits)", bad);
    /* tangent to the outer and the inner equator */
    tex_object_spans(&ob, tex_v3_make(-4, 0, R + r + 1e-9), tex_v3_make(1, 0, 0), &s);
    CHECKF(s.n == 0, "ray just outside the outer equator misses (%d)", s.n);
    tex_object_spans(&ob, tex_v3_make(-4, 0, R - r - 1e-9), tex_v3_make(1, 0, 0), &s);
    CHECKF(s.n == 2, "ray just inside the inner equator crosses the tube twice (%d)", s.n);
}

/* Random rays against a brute-force walk: every point farther than 1e-7 from
 * a reported crossing is inside an interval exactly when it is in the solid. */
static void test_random(void)
{
    tex_rng rng;
    tex_rng_seed(&rng, 9);
    int wrong = 0, rays = 3000;
    for (int i = 0; i < rays; i++) {
        double R = 0.2 + 2 * tex_rng_uniform(&rng), r = 0.05 + 1.5 * tex_rng_uniform(&rng);
        struct tex_object ob = torus(R, r);
        tex_v3 o = tex_v3_make(6 * tex_rng_uniform(&rng) - 3, 6 * tex_rng_uniform(&rng) - 3, -6);
        tex_v3 to = tex_v3_make(2 * tex_rng_uniform(&rng) - 1, r * (2 * tex_rng_uniform(&rng) - 1),
                                2 * tex_rng_uniform(&rng) - 1);
        tex_v3 d = tex_v3_norm(tex_v3_sub(to, o));
        struct tex_spans s;
        tex_object_spans(&ob, o, d, &s);
        for (int k = 0; k <= 2000; k++) {
            double t = 12.0 * k / 2000;
            int in = 0, near = 0;
            for (int j = 0; j < s.n; j++) {
                in |= t > s.in[j].t && t < s.out[j].t;
                near |= fabs(t - s.in[j].t) < 1e-7 || fabs(t - s.out[j].t) < 1e-7;
            }
            if (!near && in != inside(R, r, tex_v3_madd(o, d, t))) {
                wrong++;
                break;
            }
        }
    }
    CHECKF(wrong == 0, "%d random rays agree with a point-by-point walk (%d disagree)", rays,
           wrong);
}

/* Seen along its axis the torus covers the annulus between the cones tangent
 * to the tube outside and inside: angles atan(R/D) +- asin(r/sqrt(R^2+D^2)). */
static void test_silhouette(void)
{
    double R = 1, r = 0.35, D = 10;
    const char *sc = "image 200 200 samples 16 ambient 1 1 1 background 0 0 0\n"
                     "camera { eye 0 10 0 look 0 0 0 up 0 0 1 fov 30 }\n"
                     "surface white { Ka 1 Kd 1 1 1 }\n"
                     "torus { major 1 minor 0.35 surface white }\n";
    tex_map *m = unit_render_text(sc, 0);
    CHECK(m != NULL, "torus scene renders");
    if (!m)
        return;
    double area = 0;
    for (size_t i = 0; i < (size_t)m->w * m->h; i++)
        area += m->px[3 * i];
    double a0 = atan(R / D), da = asin(r / sqrt(R * R + D * D));
    double ppu = 200 / (2 * tan(15 * M_PI / 180)), to = tan(a0 + da) * ppu, ti = tan(a0 - da) * ppu;
    double want = M_PI * (to * to - ti * ti);
    CHECKF(fabs(area - want) < 0.01 * want,
           "torus silhouette along its axis %.1f px vs projected annulus %.1f px", area, want);
    CHECKF(tex_map_px(m, 100, 100)[0] == 0, "the hole shows the background");
    tex_map_free(m);
}

/* A slab 0.4 thick minus a torus (R 1, r 0.5) seen from far above: the hole
 * through it is the annulus |rho - R| < sqrt(r^2 - 0.2^2), area 4 pi R w. */
static void test_difference(void)
{
    const char *sc = "image 200 200 ambient 1 1 1 background 0 0 0\n"
                     "camera { eye 0 1000 0 look 0 0 0 up 0 0 1 fov 0.3 }\n"
                     "surface white { Ka 1 Kd 1 1 1 }\n"
                     "difference { box { min -2 -0.2 -2 max 2 0.2 2 }\n"
                     "             torus { major 1 minor 0.5 } surface white }\n";
    tex_map *m = unit_render_text(sc, 0);
    CHECK(m != NULL, "CSG difference with a torus renders");
    if (!m)
        return;
    double ppu = 200 / (2 * 1000 * tan(0.15 * M_PI / 180)), hole = 0;
    for (int y = 0; y < 200; y++)
        for (int x = 0; x < 200; x++)
            if (fabs(x + 0.5 - 100) < 1.9 * ppu && fabs(y + 0.5 - 100) < 1.9 * ppu)
                hole += tex_map_px(m, x, y)[0] < 0.5;
    double w = sqrt(0.25 - 0.04), want = 4 * M_PI * w * ppu * ppu;
    CHECKF(fabs(hole - want) < 0.02 * want, "annular hole through the slab %.0f px vs %.0f px",
           hole, want);
    tex_map_free(m);
}

/* Transforms: a torus turned onto the x axis and moved keeps its crossings. */
static void test_transform(void)
{
    const char *sc = "torus { major 2 minor 0.5 axis 1 0 0 centre 1 2 3 }\n"
                     "torus { major 2 minor 0.5 rotate 0 0 90 translate 1 2 3 }\n";
    struct tex_scene *s = tex_scene_parse(sc, strlen(sc), "t.scene");
    CHECKF(s && s->nobjects == 2, "torus with axis and transforms parses%s%s", s ? "" : ": ",
           s ? "" : tex_errmsg());
    if (!s)
        return;
    for (int i = 0; i < 2; i++) {
        struct tex_spans sp;
        tex_object_spans(s->objects[i], tex_v3_make(-5, 2, 3), tex_v3_make(1, 0, 0), &sp);
        int axis_ok = sp.n == 0;
        tex_object_spans(s->objects[i], tex_v3_make(1, -5, 3), tex_v3_make(0, 1, 0), &sp);
        double want[4] = {4.5, 5.5, 8.5, 9.5}, err = 0;
        if (sp.n == 2)
            err = fmax(fmax(fabs(sp.in[0].t - want[0]), fabs(sp.out[0].t - want[1])),
                       fmax(fabs(sp.in[1].t - want[2]), fabs(sp.out[1].t - want[3])));
        CHECKF(axis_ok && sp.n == 2 && err < 1e-9,
               "placed torus %d: hole along its axis, 4 crossings across (error %g)", i, err);
        tex_v3 P = tex_v3_make(1, 2 + 2.5, 3), n;
        n = tex_shape_methods[TEX_SHAPE_TORUS].normal(s->objects[i],
                                                     tex_xform_point(&s->objects[i]->to_obj, P));
        n = tex_v3_norm(tex_xform_normal(&s->objects[i]->to_obj, n));
        CHECKF(fabs(n.y - 1) < 1e-12, "outer normal points away from the tube (%g %g %g)", n.x,
               n.y, n.z);
    }
    tex_scene_free(s);
}

/* torus_map: u around the major circle, v around the tube from the top. */
static void test_map(void)
{
    struct tex_object ob = torus(2, 0.5);
    double u, v, err = 0;
    for (int i = 0; i < 16; i++) {
        for (int j = 0; j < 16; j++) {
            double a = 2 * M_PI * (i + 0.5) / 16, b = 2 * M_PI * (j + 0.5) / 16;
            double rho = 2 + 0.5 * sin(b);
            tex_v3 p = tex_v3_make(rho * cos(a), 0.5 * cos(b), -rho * sin(a));
            tex_shape_methods[TEX_SHAPE_TORUS].uv(&ob, p, &u, &v);
            err = fmax(err, fmax(fabs(u - (i + 0.5) / 16), fabs(v - (j + 0.5) / 16)));
        }
    }
    CHECKF(err < 1e-12, "torus_map inverts the torus's parametrisation (worst %g)", err);
}

/* A shadow ray's segment (tmin, tmax): whether tex_leaf_spans puts a crossing in it, as
 * tex_scene_transmit counts them */
static int crosses(const struct tex_object *ob, tex_v3 o, tex_v3 d, double tmin, double tmax)
{
    struct tex_spans s;
    tex_leaf_spans(ob, &o, &d, &s);
    for (int j = 0; j < s.n; j++)
        if ((s.in[j].t > tmin && s.in[j].t < tmax) || (s.out[j].t > tmin && s.out[j].t < tmax))
            return 1;
    return 0;
}

static tex_v3 random_dir(tex_rng *rng, double len)
{
    double z = 2 * tex_rng_uniform(rng) - 1, a = 6.283185307179586 * tex_rng_uniform(rng);
    double s = sqrt(1 - z * z);
    return tex_v3_make(len * s * cos(a), len * z, len * s * sin(a));
}

/* tex_leaf_segment's sure answers are the spans' own: shadow rays leaving the surface (a
 * hit point, nudged either way by the renderer's offsets or not at all) in every
 * direction, and segments from anywhere near, ring and spindle tori; and it answers
 * most of the rays leaving the surface, which it is there for. */
static void test_segment(void)
{
    tex_rng rng;
    tex_rng_seed(&rng, 63);
    int wrong = 0, rays = 0, leaving = 0, sure = 0;
    for (int i = 0; i < 4000; i++) {
        double R = 2 * tex_rng_uniform(&rng), r = 0.05 + 1.2 * tex_rng_uniform(&rng);
        struct tex_object ob = torus(R, r);
        tex_v3 o = random_dir(&rng, 3 * (R + r)), d = tex_v3_scale(o, -1);
        struct tex_spans s;
        tex_object_spans(&ob, o, d, &s);
        for (int k = 0; k < 8; k++) {
            double tmin = 0, tmax = k == 7 ? INFINITY : 0.1 + 20 * tex_rng_uniform(&rng);
            tex_v3 from = o, dir = random_dir(&rng, 0.25 + tex_rng_uniform(&rng));
            int out = 0;
            if (s.n && k < 6) { /* from the surface, nudged out, in or not at all */
                int enter = tex_rng_uniform(&rng) < 0.5;
                from = tex_v3_madd(o, d, (enter ? s.in[0].t : s.out[0].t) + (k % 3 - 1) * 3e-6);
                out = k % 3 == (enter ? 0 : 2);
                leaving += out;
            } else { /* from anywhere near, over any piece */
                from = tex_v3_scale(random_dir(&rng, 1), (R + r) * 1.5 * tex_rng_uniform(&rng));
                tmin = 0.5 * tex_rng_uniform(&rng);
            }
            int a = tex_leaf_segment(&ob, &from, &dir, tmin, tmax);
            int truth = crosses(&ob, from, dir, tmin, tmax);
            wrong += (a > 0 && !truth) || (a < 0 && truth);
            sure += a != 0 && out;
            rays++;
        }
    }
    CHECKF(wrong == 0, "%d segments: every sure answer of tex_leaf_segment is the spans' (%d not)",
           rays, wrong);
    CHECKF(sure > leaving / 2, "it answers %d of %d rays from just outside the surface (more than half)",
           sure, leaving);
}

int main(void)
{
    test_crossings();
    test_grazing();
    test_random();
    test_segment();
    test_silhouette();
    test_difference();
    test_transform();
    test_map();
    return unit_done();
}
