/* test_geometry_box - box2 of the geometric primitives: a box it calls one
 * region holds no point of another (random boxes, many near the edges, thin
 * features included, rows and single points too, as --ids asks), and it does
 * call most small boxes one region */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "textura.h"
#include "unit.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15u;

static double rnd(void) /* [0, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static int id_at(const struct tex_field *f, double u, double v)
{
    float id;
    f->prim->eval2(f, 1, &u, &v, &id);
    return (int)id;
}

/* A point within about 1e-12 of an edge between two random points of
 * different regions, or a random point when they agree. */
static void near_edge(const struct tex_field *f, double *u, double *v)
{
    double u0 = rnd(), v0 = rnd(), a = 2 * M_PI * rnd(), d = 0.1 * rnd();
    double u1 = u0 + d * cos(a), v1 = v0 + d * sin(a);
    int k0 = id_at(f, u0, v0);
    if (u1 < 0 || u1 >= 1 || v1 < 0 || v1 >= 1 || id_at(f, u1, v1) == k0) {
        *u = u0;
        *v = v0;
        return;
    }
    for (int i = 0; i < 45; i++) {
        double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
        if (id_at(f, um, vm) == k0)
            u0 = um, v0 = vm;
        else
            u1 = um, v1 = vm;
    }
    *u = u0;
    *v = v0;
}

struct box_case {
    const char *prim;
    const char *kv[5];
    double min_proven; /* the share of random boxes of 1e-3 a side that box2 must prove */
};

static const struct box_case cases[] = {
    {"circle", {NULL}, 0.9},
    {"circle", {"radius=0.7", "nu=3", NULL}, 0.9},
    {"ring", {"ring_width=0.0007", NULL}, 0.9},
    {"ring", {"radius=0.3", "ring_width=0.3", NULL}, 0.9},
    {"ellipse", {"angle=30", NULL}, 0.9},
    {"ellipse", {"semi_major=0.48", "semi_minor=0.1", "band_width=0.001", "angle=-70", NULL}, 0.8},
    {"flower", {NULL}, 0.8},
    {"flower", {"petals=40", NULL}, 0},
    {"flower", {"petals=997", "nu=2", NULL}, 0},
    {"checker", {NULL}, 0.9},
    {"checker", {"nu=4096", "nv=7", NULL}, 0},
    {"stripe", {NULL}, 0.9},
    {"stripe", {"angle=17", "stripe_width=0.001", "spacing=0.03", NULL}, 0.8},
    {"stripe", {"spacing=0", NULL}, 0.8},
    {"cycloid", {NULL}, 0.9},
    {"cycloid", {"radius=60", "arch_width=0.0005", NULL}, 0.9},
    {"hypocycloid", {NULL}, 0.9},
    {"hypocycloid", {"radius=0.6", "band_width=0.001", NULL}, 0.9},
    {"four_rings", {NULL}, 0.9},
    {"four_rings", {"radius=0.4", "ring_width=0.0008", NULL}, 0.8},
    {"polygon", {NULL}, 0.9},
    {"polygon", {"sides=1000", "angle=13", NULL}, 0.9},
    {"star", {NULL}, 0.9},
    {"star", {"sides=97", "inner_radius=0.05", NULL}, 0.5},
    {"star", {"sides=2", "inner_radius=0", NULL}, 0.9},
    {"grid", {NULL}, 0.9},
    {"grid", {"line_width=0.002", "nu=13", NULL}, 0.8},
    {"brick", {NULL}, 0.9},
    {"brick", {"mortar_width=0", NULL}, 0.9},
    {"brick", {"cells=1", "nu=5", "nv=3", NULL}, 0.9},
    {"dots", {NULL}, 0.9},
    {"dots", {"radius=0.002", "nu=9", NULL}, 0.9},
};

static void one_case(const struct box_case *c)
{
    const struct tex_primitive *p = tex_primitive_find(c->prim);
    struct tex_field *f = p ? tex_field_new(p) : NULL;
    char label[160];
    int n = snprintf(label, sizeof label, "%s", c->prim);
    long proven = 0, wrong = 0, small = 0, small_proven = 0;

    for (int i = 0; c->kv[i]; i++) {
        char key[64];
        const char *eq = strchr(c->kv[i], '=');
        n += snprintf(label + n, sizeof label - n, " %s", c->kv[i]);
        snprintf(key, sizeof key, "%.*s", (int)(eq - c->kv[i]), c->kv[i]);
        if (f && tex_field_set(f, key, eq + 1) < 0) {
            tex_field_free(f);
            f = NULL;
        }
    }
    if (!f || tex_field_init(f, 512, 384) < 0) {
        CHECKF(0, "%s: field made", label);
        tex_field_free(f);
        return;
    }
    for (int t = 0; t < 6000; t++) {
        double u, v, hu, hv;
        float k;
        int plain = t % 3 == 0;
        if (plain) {
            u = rnd();
            v = rnd();
            hu = hv = 5e-4;
        } else {
            near_edge(f, &u, &v);
            double r = rnd();
            hu = pow(10, -6 + 4.5 * rnd());
            /* a quarter one row of points (hv 0), as --ids's spans; a tenth of those one point */
            hv = r < 0.25 ? 0 : r < 0.5 ? hu : pow(10, -6 + 4.5 * rnd());
            if (r < 0.025)
                hu = 0;
            u += (2 * rnd() - 1) * 3 * hu;
            v += (2 * rnd() - 1) * 3 * hv;
            if (u < 0 || u >= 1 || v < 0 || v >= 1)
                continue;
        }
        p->box2(f, 1, &u, &v, hu, hv, &k);
        small += plain;
        if (k == 0)
            continue;
        proven++;
        small_proven += plain;
        /* the box's corners, a 9 x 9 lattice and random points: all region k */
        for (int j = 0; j < 81 + 40; j++) {
            double du = j < 81 ? (j % 9) / 4.0 - 1 : 2 * rnd() - 1;
            double dv = j < 81 ? (j / 9) / 4.0 - 1 : 2 * rnd() - 1;
            if (id_at(f, u + du * hu, v + dv * hv) != (int)k) {
                if (wrong++ < 3)
                    printf("# %s: box %.17g +- %g, %.17g +- %g called %d, but (%+g, %+g) is %d\n",
                           label, u, hu, v, hv, (int)k, du, dv,
                           id_at(f, u + du * hu, v + dv * hv));
                break;
            }
        }
    }
    CHECKF(wrong == 0 && proven > 0, "%s: %ld boxes called one region, %ld wrongly", label, proven,
           wrong);
    if (c->min_proven > 0)
        CHECKF(small_proven >= c->min_proven * small,
               "%s: box2 proves %ld of %ld random boxes of 1e-3 (at least %g)", label,
               small_proven, small, c->min_proven);
    tex_field_free(f);
}

int main(void)
{
    for (int i = 0; tex_primitives[i]; i++) {
        const struct tex_primitive *p = tex_primitives[i];
        if ((p->flags & TEX_PRIM_REGIONS) && !(p->flags & TEX_PRIM_GRID))
            CHECKF(p->box2 != NULL, "%s: has box2, so colour maps subsample only edges", p->name);
    }
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        one_case(&cases[i]);
    return unit_done();
}
