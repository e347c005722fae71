/* test_geometry - the geometric primitives: regions at known points, areas,
 * symmetry, repetition, antialiasing and bad parameters */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "textura.h"
#include "base/simd.h"
#include "unit.h"

/* A field of primitive name with "key=value" settings, ready for a w x h grid. */
static struct tex_field *field(const char *name, int ids, int w, int h, ...)
{
    const struct tex_primitive *p = tex_primitive_find(name);
    struct tex_field *f = p ? tex_field_new(p) : NULL;
    const char *kv;
    va_list ap;

    if (!f)
        return NULL;
    f->ids = ids;
    va_start(ap, h);
    while ((kv = va_arg(ap, const char *))) {
        char key[64];
        const char *eq = strchr(kv, '=');
        snprintf(key, sizeof key, "%.*s", (int)(eq - kv), kv);
        if (tex_field_set(f, key, eq + 1) < 0) {
            printf("# %s\n", tex_errmsg());
            tex_field_free(f);
            va_end(ap);
            return NULL;
        }
    }
    va_end(ap);
    if (tex_field_init(f, w, h) < 0) {
        printf("# %s\n", tex_errmsg());
        tex_field_free(f);
        return NULL;
    }
    return f;
}

/* Region at cell point (x right, y up), as a test reads the figures. */
static int at(const struct tex_field *f, double x, double y)
{
    return tex_geometry_region(f, x, 1 - y);
}

/* Regions at known points of the round primitives: circle, ring, ellipse, flower */
static void known_points_round(void)
{
    struct tex_field *f;

    f = field("circle", 1, 0, 0, NULL);
    CHECK(at(f, 0.5, 0.5) == 2 && at(f, 0.01, 0.01) == 1 && at(f, 0.89, 0.5) == 2 &&
              at(f, 0.91, 0.5) == 1,
          "circle: centre 2, corner 1, edge at r = 0.4");
    tex_field_free(f);

    f = field("ring", 1, 0, 0, "radius=0.4", "ring_width=0.12", NULL);
    CHECK(at(f, 0.5, 0.5) == 3 && at(f, 0.5 + 0.35, 0.5) == 2 && at(f, 0.5, 0.5 - 0.35) == 2 &&
              at(f, 0.5 + 0.27, 0.5) == 3 && at(f, 0.99, 0.99) == 1,
          "ring: centre 3, band 2 at 0.28 < dist <= 0.4, corner 1");
    tex_field_free(f);

    f = field("ellipse", 1, 0, 0, "semi_major=0.45", "semi_minor=0.3", "band_width=0.08", NULL);
    CHECK(at(f, 0.5, 0.5) == 3 && at(f, 0.5 + 0.42, 0.5) == 2 && at(f, 0.5, 0.5 + 0.42) == 1 &&
              at(f, 0.5, 0.5 + 0.25) == 2 && at(f, 0.02, 0.5) == 1,
          "ellipse: major axis horizontal, centre 3");
    tex_field_free(f);

    f = field("ellipse", 1, 0, 0, "angle=90", NULL);
    CHECK(at(f, 0.5, 0.5 + 0.42) == 2 && at(f, 0.5 + 0.42, 0.5) == 1,
          "ellipse: --angle 90 turns the major axis upright");
    tex_field_free(f);

    /* n = 5: petals point at theta = pi/10 + 2k pi/5, gaps at 3pi/10 + 2k pi/5. */
    f = field("flower", 1, 0, 0, "petals=5", "petal_length=0.45", NULL);
    CHECK(at(f, 0.5 + 0.4 * cos(M_PI / 10), 0.5 + 0.4 * sin(M_PI / 10)) == 2 &&
              at(f, 0.5 + 0.2 * cos(3 * M_PI / 10), 0.5 + 0.2 * sin(3 * M_PI / 10)) == 1 &&
              at(f, 0.5, 0.5 + 0.4) == 2 && at(f, 0.5, 0.5 - 0.2) == 1 && at(f, 0.01, 0.01) == 1,
          "flower 5: on a petal 2, between petals 1 (a petal straight up, none down)");
    tex_field_free(f);

    /* the ids at 45, 225, 135 and 315 degrees, 0.3 from the centre, and on the right */
    static const struct {
        const char *arg, *what;
        int id[5];
    } twos[] = {{"rose=2", "rose 2: four petals on the diagonals", {2, 2, 2, 2, 1}},
                {"petals=2", "flower 2 petals: two, on one diagonal", {2, 2, 1, 1, 1}}};
    for (int t = 0; t < 2; t++) {
        static const double deg[5] = {45, 225, 135, 315, 0};
        int good = 1;
        f = field("flower", 1, 0, 0, twos[t].arg, NULL);
        for (int i = 0; i < 5; i++)
            good &= at(f, 0.5 + 0.3 * cos(deg[i] * M_PI / 180),
                       0.5 + 0.3 * sin(deg[i] * M_PI / 180)) == twos[t].id[i];
        CHECK(good, twos[t].what);
        tex_field_free(f);
    }
}

/* ... and of the others: checker, stripe, the cycloids, four rings, polygon, star */
static void known_points_other(void)
{
    struct tex_field *f;

    f = field("checker", 1, 0, 0, NULL);
    CHECK(tex_geometry_region(f, 0.05, 0.05) == 1 && tex_geometry_region(f, 0.18, 0.05) == 2 &&
              tex_geometry_region(f, 0.05, 0.18) == 2 && tex_geometry_region(f, 0.18, 0.18) == 1 &&
              tex_geometry_region(f, 0.95, 0.95) == 1,
          "checker: 8x8 board by default, top-left square 1");
    tex_field_free(f);

    f = field("stripe", 1, 0, 0, "angle=90", "stripe_width=0.1", "spacing=0.15", NULL);
    CHECK(at(f, 0.5, 0.1) == 2 && at(f, 0.56, 0.9) == 1 && at(f, 0.75, 0.3) == 2 &&
              at(f, 0.62, 0.5) == 1,
          "stripe: vertical at 90 degrees, one centred, period 0.25");
    tex_field_free(f);

    /* a = 1/(2 pi): the arch is 1/pi high; the inner one 0.08 lower. */
    f = field("cycloid", 1, 0, 0, NULL);
    CHECK(at(f, 0.5, 0.01) == 3 && at(f, 0.5, 0.28) == 2 && at(f, 0.5, 0.33) == 1 &&
              at(f, 0.5, 0.99) == 1 && at(f, 0.005, 0.05) == 1 && at(f, 0.2, 0.05) == 3,
          "cycloid: arch on the bottom side, inside 3, band 2, above 1");
    tex_field_free(f);

    f = field("hypocycloid", 1, 0, 0, "radius=0.45", "band_width=0.1", NULL);
    CHECK(at(f, 0.5, 0.5) == 3 && at(f, 0.5 + 0.4, 0.5) == 2 && at(f, 0.5, 0.5 - 0.4) == 2 &&
              at(f, 0.7, 0.7) == 1 && at(f, 0.5 + 0.3, 0.5) == 3,
          "hypocycloid: cusps on the axes, concave sides");
    tex_field_free(f);

    f = field("four_rings", 1, 0, 0, "radius=0.2", "ring_width=0.06", NULL);
    CHECK(at(f, 0.25 + 0.17, 0.25) == 2 && at(f, 0.75, 0.75 - 0.17) == 2 && at(f, 0.25, 0.25) == 1 &&
              at(f, 0.5, 0.5) == 1 && at(f, 0.75 - 0.17, 0.25) == 2,
          "four_rings: a ring round each quarter's centre");
    tex_field_free(f);

    f = field("polygon", 1, 0, 0, "sides=4", "radius=0.4", "angle=0", NULL);
    CHECK(at(f, 0.5 + 0.39, 0.5) == 2 && at(f, 0.5 + 0.21, 0.5 + 0.21) == 1 &&
              at(f, 0.5 + 0.19, 0.5 + 0.19) == 2,
          "polygon: a square with vertices on the axes");
    tex_field_free(f);
    f = field("star", 1, 0, 0, "sides=5", "radius=0.45", NULL);
    CHECK(at(f, 0.5, 0.5 + 0.44) == 2 && at(f, 0.5, 0.5 - 0.3) == 1 && at(f, 0.5, 0.5) == 2,
          "star: a point straight up, a notch straight down");
    tex_field_free(f);
}

/* Fraction of the n x n --ids map in region k. */
static double area(const struct tex_field *f, int k)
{
    tex_map *m = tex_field_sample(f);
    size_t c = 0, n = tex_map_samples(m);
    for (size_t i = 0; i < n; i++)
        c += m->px[i] == k;
    tex_map_free(m);
    return (double)c / n;
}

#define N 512
static void check_area(const char *what, const struct tex_field *f, int k, double want)
{
    double got = area(f, k);
    CHECKF(fabs(got - want) < 0.003, "%s: area %.5f vs %.5f", what, got, want);
}

static void areas(void)
{
    struct tex_field *f;
    double a, r, d;

    f = field("circle", 1, N, N, "radius=0.3", NULL);
    check_area("circle inside, pi r^2", f, 2, M_PI * 0.09);
    check_area("circle outside, 1 - pi r^2", f, 1, 1 - M_PI * 0.09);
    tex_field_free(f);

    r = 0.4, d = 0.15;
    f = field("ring", 1, N, N, "radius=0.4", "ring_width=0.15", NULL);
    check_area("ring band", f, 2, M_PI * (r * r - (r - d) * (r - d)));
    check_area("ring inside", f, 3, M_PI * (r - d) * (r - d));
    tex_field_free(f);

    f = field("ellipse", 1, N, N, "semi_major=0.4", "semi_minor=0.25", "band_width=0.05",
    "angle=30", NULL);
    check_area("ellipse band, pi M m - pi (M-d)(m-d)", f, 2, M_PI * (0.4 * 0.25 - 0.35 * 0.2));
    check_area("ellipse inside", f, 3, M_PI * 0.35 * 0.2);
    tex_field_free(f);

    f = field("flower", 1, N, N, "petals=5", "petal_length=0.45", NULL);
    check_area("flower, odd n: pi d^2/4", f, 2, M_PI * 0.45 * 0.45 / 4);
    tex_field_free(f);
    f = field("flower", 1, N, N, "petals=4", "petal_length=0.45", NULL);
    check_area("flower, 4 petals: pi d^2/4", f, 2, M_PI * 0.45 * 0.45 / 4);
    tex_field_free(f);
    f = field("flower", 1, N, N, "rose=4", "petal_length=0.45", NULL);
    check_area("rose, even n: pi d^2/2", f, 2, M_PI * 0.45 * 0.45 / 2);
    tex_field_free(f);

    f = field("checker", 1, N, N, "nu=3", "nv=5", NULL);
    check_area("checker: half", f, 1, 0.5);
    tex_field_free(f);

    f = field("stripe", 1, N, N, "angle=90", "stripe_width=0.1875", "spacing=0.0625", NULL);
    check_area("stripe at 90: l/(l+d)", f, 2, 0.75);
    tex_field_free(f);
    f = field("stripe", 1, N, N, "angle=30", "stripe_width=0.05", "spacing=0.1", NULL);
    check_area("stripe at 30: l/(l+d)", f, 2, 1.0 / 3);
    tex_field_free(f);

    /* The area under a cycloid arch is 3 pi a^2. */
    a = 1 / (2 * M_PI);
    f = field("cycloid", 1, N, N, "radius=100", "arch_width=0.1", NULL);
    check_area("cycloid band", f, 2, 3 * M_PI * (a * a - (a - 0.05) * (a - 0.05)));
    check_area("cycloid inside", f, 3, 3 * M_PI * (a - 0.05) * (a - 0.05));
    tex_field_free(f);

    /* The area inside an astroid is 3 pi a^2 / 8. */
    f = field("hypocycloid", 1, N, N, "radius=0.45", "band_width=0.15", NULL);
    check_area("hypocycloid band", f, 2, 3 * M_PI * (0.45 * 0.45 - 0.3 * 0.3) / 8);
    check_area("hypocycloid inside", f, 3, 3 * M_PI * 0.3 * 0.3 / 8);
    tex_field_free(f);

    f = field("four_rings", 1, N, N, "radius=0.2", "ring_width=0.05", NULL);
    check_area("four_rings", f, 2, 4 * M_PI * (0.2 * 0.2 - 0.15 * 0.15));
    tex_field_free(f);

    f = field("polygon", 1, N, N, "sides=7", "radius=0.45", "angle=10", NULL);
    check_area("polygon: n r^2 sin(2pi/n) / 2", f, 2, 3.5 * 0.45 * 0.45 * sin(2 * M_PI / 7));
    tex_field_free(f);
    f = field("star", 1, N, N, "sides=5", "radius=0.45", "inner_radius=0.4", NULL);
    check_area("star: n r r_i sin(pi/n)", f, 2, 5 * 0.45 * 0.18 * sin(M_PI / 5));
    tex_field_free(f);
    f = field("grid", 1, N, N, "nu=4", "nv=4", "line_width=0.25", NULL);
    check_area("grid: 1 - (1-d)^2", f, 2, 1 - 0.75 * 0.75);
    tex_field_free(f);
    f = field("dots", 1, N, N, "radius=0.25", NULL);
    check_area("dots: two per cell", f, 2, 2 * M_PI * 0.0625);
    tex_field_free(f);
    /* Square map, nu = nv: bed joints d of a course, head joints as wide on the map,
     * d/2 of a brick's length. */
    f = field("brick", 1, N, N, "nu=4", "nv=4", "mortar_width=0.25", NULL);
    check_area("brick mortar", f, 2, 1 - (1 - 0.25) * (1 - 0.125));
    tex_field_free(f);
}

/* Does rotating by angle about the centre keep every region? */
static int mismatches(const struct tex_field *f, double angle)
{
    tex_rng r;
    int bad = 0;
    tex_rng_seed(&r, 7);
    for (int i = 0; i < 4000; i++) {
        double rho = 0.5 * tex_rng_uniform(&r), t = 2 * M_PI * tex_rng_uniform(&r);
        bad += at(f, 0.5 + rho * cos(t), 0.5 + rho * sin(t)) !=
               at(f, 0.5 + rho * cos(t + angle), 0.5 + rho * sin(t + angle));
    }
    return bad;
}

static void symmetry(void)
{
    static const char *ns[] = {"3", "5", "7", "2", "4", "6"};
    for (int i = 0; i < 12; i++) {
        int n = atoi(ns[i % 6]), rose = i >= 6;
        char arg[32];
        snprintf(arg, sizeof arg, "%s=%d", rose ? "rose" : "petals", n);
        struct tex_field *f = field("flower", 1, 0, 0, arg, NULL);
        /* n petals repeat every 2pi/n; the whole rose of an even n every pi/n */
        int half = rose && n % 2 == 0;
        double step = half ? M_PI / n : 2 * M_PI / n;
        CHECKF(mismatches(f, step) == 0, "flower %s invariant under rotation by %s/%d", arg,
               half ? "pi" : "2pi", n);
        CHECKF(mismatches(f, step / 2) > 400, "flower %s not invariant under half that", arg);
        tex_field_free(f);
    }
}

/* A nu x nv map equals the single pattern's map tiled. */
static void repetition(void)
{
    const char *prims[] = {"circle", "flower", "cycloid", "stripe", "brick", "star"};
    for (int i = 0; i < 6; i++) {
        for (int ids = 0; ids <= 1; ids++) {
            struct tex_field *one = field(prims[i], ids, 48, 40, "nu=1", "nv=1", NULL);
            struct tex_field *rep = field(prims[i], ids, 144, 80, "nu=3", "nv=2", NULL);
            tex_map *a = tex_field_sample(one), *b = tex_field_sample(rep);
            double worst = 0;
            for (int y = 0; y < b->h; y++)
                for (int x = 0; x < b->w; x++)
                    for (int c = 0; c < b->nc; c++)
                        worst = fmax(worst, fabs(tex_map_px(b, x, y)[c] -
                                                 tex_map_px(a, x % 48, y % 40)[c]));
            CHECKF(a->nc == (ids ? 1 : 3) && worst < 1e-6,
                   "%s %s: nu 3 x nv 2 is the pattern tiled (worst %g)", prims[i],
                   ids ? "ids" : "colours", worst);
            tex_map_free(a);
            tex_map_free(b);
            tex_field_free(one);
            tex_field_free(rep);
        }
    }
}

static void ids_and_colours(void)
{
    struct tex_field *f = field("ring", 1, 64, 64, NULL);
    tex_map *m = tex_field_sample(f);
    int integral = 1, seen[4] = {0};
    for (size_t i = 0; i < tex_map_samples(m); i++) {
        float v = m->px[i];
        integral &= v == floorf(v) && v >= 1 && v <= 3;
        if (v >= 1 && v <= 3)
            seen[(int)v] = 1;
    }
    CHECK(m->nc == 1 && m->subregions == 3 && integral && seen[1] && seen[2] && seen[3],
          "ring --ids: one channel of exact ids 1..3, subregions 3");
    tex_map_free(m);
    tex_field_free(f);

    /* Colours: interior pixels exact, edge pixels a mix of the two colours. */
    f = field("circle", 0, 64, 64, "color1=0,0,0", "color2=1,0.5,0.25", NULL);
    m = tex_field_sample(f);
    int mixed = 0, on_segment = 1;
    for (int i = 0; i < 64 * 64; i++) {
        const float *p = m->px + 3 * i;
        if (p[0] > 0 && p[0] < 1)
            mixed++;
        on_segment &= fabsf(p[1] - 0.5f * p[0]) < 1e-6f && fabsf(p[2] - 0.25f * p[0]) < 1e-6f;
    }
    CHECK(m->nc == 3 && m->subregions == 0, "circle in colour: RGB, no subregions");
    CHECK(tex_map_px(m, 32, 32)[0] == 1 && tex_map_px(m, 32, 32)[1] == 0.5f &&
              tex_map_px(m, 0, 0)[0] == 0,
          "circle in colour: inside and outside pixels are exactly their colours");
    /* The edge crosses about 2 pi r 64 = 161 pixels. */
    CHECKF(mixed > 100 && mixed < 400, "circle in colour: %d antialiased edge pixels", mixed);
    CHECK(on_segment, "circle in colour: every pixel mixes the two region colours");
    tex_map_free(m);
    tex_field_free(f);
}

static void threads(void)
{
#ifdef _OPENMP
    struct tex_field *f = field("flower", 0, 97, 61, "petals=7", NULL);
    omp_set_num_threads(1);
    tex_map *a = tex_field_sample(f);
    omp_set_num_threads(3);
    tex_map *b = tex_field_sample(f);
    CHECK(memcmp(a->px, b->px, tex_map_samples(a) * sizeof(float)) == 0,
          "flower in colour: same bytes with 1 and 3 threads");
    tex_map_free(a);
    tex_map_free(b);
    tex_field_free(f);
#endif
}

static void solids(void)
{
    struct tex_field *f = field("ring", 1, 0, 0, NULL);
    double u[3] = {0.5, 0.5, 0.5}, v[3] = {0.5, 0.5, 0.5}, w[3] = {0.5, 0.5 + 0.35, 0.95};
    float out[3];
    f->prim->eval3(f, 3, u, v, w, out);
    CHECK(out[0] == 3 && out[1] == 2 && out[2] == 1, "ring solid: concentric spheres");
    tex_field_free(f);

    f = field("checker", 1, 0, 0, "nu=1", "nv=1", "nw=1", NULL);
    double cu[4] = {0.2, 0.7, 0.2, 0.7}, cv[4] = {0.2, 0.2, 0.2, 0.7}, cw[4] = {0.2, 0.2, 0.7, 0.2};
    float co[4];
    f->prim->eval3(f, 4, cu, cv, cw, co);
    CHECK(co[0] == 1 && co[1] == 2 && co[2] == 2 && co[3] == 1, "checker solid: 3D parity");
    tex_field_free(f);

    f = field("circle", 1, 0, 0, NULL);
    f->prim->eval3(f, 3, u, v, w, out);
    CHECK(out[0] == 2 && out[2] == 1, "circle solid: a ball");
    tex_field_free(f);
}

/* A coordinate of the checker's tests: on a cell's face (k / 2, its half-cell faces), a
 * rounding beside it, zeros, NaN, infinities, the largest and smallest doubles, and beyond
 * 2^52 where every double is whole */
static double cell_coord(unsigned k)
{
    static const double odd[] = {0.0, -0.0, NAN, INFINITY, -INFINITY, 1e300, -1e300,
                                 4503599627370497.0, -4503599627370497.0, 0x1p53, 5e-324, -5e-324};
    double x = ((int)(k % 41) - 20) / 2.0, near[3] = {x, nextafter(x, -1e9), nextafter(x, 1e9)};
    if (k % 7 == 0)
        return odd[k / 7 % (sizeof odd / sizeof *odd)];
    return k % 5 == 0 ? x - 0.5e-10 : near[k / 41 % 3]; /* the cell's epsilon, at its edge */
}

/* The solid checker's kernel in vector lanes gives the portable cells, bit for bit, at every
 * level, on faces, beside them and at the odd values */
static void checker_levels(void)
{
    int reps[3][3] = {{1, 1, 1}, {3, 5, 2}, {4096, 7, 1}}, levels[2] = {tex_simd_level(), 0};
    int n = 1003, bad = 0, two = 0; /* n: not a multiple of the lanes */
    double *u = malloc(3 * n * sizeof *u), *v = u + n, *w = v + n;
    float *out = malloc(2 * n * sizeof *out);
    for (int i = 0; i < n; i++)
        u[i] = cell_coord(i), v[i] = cell_coord(3 * i + 1), w[i] = cell_coord(7 * i + 2);
    for (int r = 0; r < 3; r++) {
        char a[3][16];
        snprintf(a[0], sizeof a[0], "nu=%d", reps[r][0]);
        snprintf(a[1], sizeof a[1], "nv=%d", reps[r][1]);
        snprintf(a[2], sizeof a[2], "nw=%d", reps[r][2]);
        struct tex_field *f = field("checker", 1, 0, 0, a[0], a[1], a[2], NULL);
        for (int l = 0; l < 2; l++) {
            tex_simd_limit(levels[l]);
            f->prim->eval3(f, n, u, v, w, out + l * n);
        }
        tex_simd_limit(levels[0]);
        for (int i = 0; i < n; i++)
            bad += memcmp(&out[i], &out[n + i], sizeof *out) != 0, two += out[i] == 2;
        tex_field_free(f);
    }
    CHECKF(bad == 0 && two > n && two < 2 * n,
           "checker solid: the AVX2 kernel's cells are the portable ones (%s; %d of %d differ, "
           "%d twos)",
           tex_simd_name(levels[0]), bad, 3 * n, two);
    free(u);
    free(out);
}

static void bad_params(void)
{
    struct {
        const char *prim, *key, *val, *key2, *val2;
    } bad[] = {
        {"ring", "ring_width", "0.5", "radius", "0.4"},
        {"ellipse", "semi_minor", "0.5", "semi_major", "0.4"},
        {"ellipse", "band_width", "0.35", "semi_minor", "0.3"},
        {"hypocycloid", "band_width", "0.5", "radius", "0.45"},
        {"four_rings", "ring_width", "0.3", "radius", "0.2"},
        {"cycloid", "arch_width", "0.2", "radius", "50"},
        {"stripe", "stripe_width", "0", "angle", "10"},
        {"flower", "petals", "0", NULL, NULL},
        {"circle", "radius", "-0.1", NULL, NULL},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        struct tex_field *f = tex_field_new(tex_primitive_find(bad[i].prim));
        int r = tex_field_set(f, bad[i].key, bad[i].val);
        if (r == 0 && bad[i].key2)
            r = tex_field_set(f, bad[i].key2, bad[i].val2);
        if (r == 0)
            r = tex_field_init(f, 8, 8);
        CHECKF(r < 0 && tex_errkind() == TEX_ERR_USAGE, "%s --%s %s refused: %s", bad[i].prim,
               bad[i].key, bad[i].val, tex_errmsg());
        tex_field_free(f);
    }
}

/* tex_field_sample_into a caller's band (an encoder's rows) makes a window's bytes of the
 * whole map, and refuses a band of another size or channel count. */
static void sample_into(void)
{
    static const struct {
        const char *name;
        int ids;
    } fs[] = {{"circle", 0}, {"ring", 1}, {"star", 0}, {"noise", 0}, {"turbulence", 0}};
    enum { W = 97, H = 61, Y0 = 10, ROWS = 17 };
    for (size_t i = 0; i < sizeof fs / sizeof *fs; i++) {
        struct tex_field *f = field(fs[i].name, fs[i].ids, W, H, NULL);
        tex_map *whole = f ? tex_field_sample(f) : NULL;
        int nc = f ? tex_field_channels(f) : 0;
        float *buf = calloc((size_t)W * ROWS * nc + 1, sizeof *buf);
        if (!whole || !buf) {
            CHECKF(0, "%s: a map to compare bands with", fs[i].name);
            tex_field_free(f), tex_map_free(whole), free(buf);
            continue;
        }
        buf[W * ROWS * nc] = 42; /* past the band: must stay */
        tex_map band = {.w = W, .h = ROWS, .nc = nc, .px = buf};
        f->wx = 0, f->wy = Y0, f->ww = W, f->wh = ROWS;
        int rc = tex_field_sample_into(f, &band);
        CHECKF(rc == 0 && nc == whole->nc && buf[W * ROWS * nc] == 42 &&
                   !memcmp(buf, tex_map_row(whole, Y0), sizeof *buf * W * ROWS * nc),
               "%s%s: a band sampled into a caller's rows is the whole map's rows %d..%d",
               fs[i].name, fs[i].ids ? " --ids" : "", Y0, Y0 + ROWS - 1);
        band.nc = nc + 1;
        rc = tex_field_sample_into(f, &band);
        CHECKF(rc < 0 && strstr(tex_errmsg(), "field"),
               "%s: a band of %d channels for %d is refused (%s)", fs[i].name, nc + 1, nc,
               tex_errmsg());
        band.nc = nc, band.h = ROWS + 1;
        CHECKF(tex_field_sample_into(f, &band) < 0 && buf[W * ROWS * nc] == 42,
               "%s: a band of %d rows for a window of %d is refused, nothing written",
               fs[i].name, ROWS + 1, ROWS);
        tex_map_free(whole);
        tex_field_free(f);
        free(buf);
    }
}

int main(void)
{
    known_points_round();
    known_points_other();
    areas();
    symmetry();
    repetition();
    ids_and_colours();
    threads();
    sample_into();
    solids();
    checker_levels();
    bad_params();
    return unit_done();
}
