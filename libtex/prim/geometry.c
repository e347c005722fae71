/* geometry.c - the geometric primitives: figures that split texture space into subregions */
#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "base/rng.h"
#include "base/simd.h"
#include "prim/cell.h"
#include "prim/geometry.h"
#include "prim/x86/geometry_x86.h"

/* Every primitive's parameter struct starts with this head, so that the
 * shared code reads repetitions and colours through struct geo_head. */
#define GEO_HEAD                                                                                   \
    int nu, nv, nw;                                                                                \
    float color1[4], color2[4], color3[4];                                                         \
    struct tex_reals centre
struct geo_head {
    GEO_HEAD;
};

struct geo_state {
    float col[3][3]; /* region colours as RGB, for f->colors */
    double k[8];     /* constants the primitive precomputes */
    double du, dv;   /* the shift of (u, v) that puts the figure's centre at (h, k) */
};

#define ROW_NU(S, d)                                                                               \
    TEX_INT(S, nu, 0, d, 1, 4096, "N", "repetitions of the pattern across the map (the thesis's nu)")
#define ROW_NV(S, d) TEX_INT(S, nv, 0, d, 1, 4096, "N", "repetitions of the pattern down the map (nv)")
#define ROW_NW(S, d) TEX_INT(S, nw, 0, d, 1, 4096, "N", "repetitions along w (solid texture only)")
/* Appendix A's center(h, k): where the figure's centre lies in its cell */
#define ROW_CENTRE(S)                                                                              \
    TEX_REALS_N("cell_centre", S, centre, 0, "0.5,0.5", -1e3, 1e3, 2, "H,K",                     \
                "the figure's centre in its cell, x right and y up (Appendix A's center(h,k)): "   \
                "0.5,0.5 the middle, 0,0 the lower-left corner")
#define ROW_COLOR(S, k, def, help) TEX_COLOR_N("colour" #k, S, color##k, 0, def, help)
/* The default colours the figures share, each written once: a warm paper ground, an ink
 * blue, an ochre and a gold */
#define PAPER "#f4efe2"
#define INK "#2b5f8a"
#define OCHRE "#e0a526"
#define GOLD "#f2c12e"

/* Position inside a repetition cell: [0,1). */
static inline double cell(double t, int n)
{
    double s = t * n;
    return s - floor(s);
}

/* cell's for a solid texture, whose surfaces may lie on the cells' faces (prim/cell.h) */
static inline double cell3(double t, int n)
{
    return tex_cell_frac(t * n);
}

static int geo_init(struct tex_field *f, int nregions)
{
    const struct geo_head *h = f->params;
    const float *c[3] = {h->color1, h->color2, h->color3};
    struct geo_state *s = calloc(1, sizeof *s);

    if (!s)
        return tex_error("out of memory");
    for (int k = 0; k < nregions && k < 3; k++)
        for (int j = 0; j < 3; j++)
            s->col[k][j] = c[k][j];
    /* 0 at the default: u - 0 is u to the bit */
    s->du = (h->centre.v[0] - 0.5) / h->nu;
    s->dv = (h->centre.v[1] - 0.5) / h->nv;
    f->state = s;
    f->nregions = nregions;
    f->colors = (const float(*)[3])s->col;
    f->nc = 1;
    return 0;
}

static void geo_fini(struct tex_field *f)
{
    free(f->state);
    f->state = NULL;
}

int tex_geometry_region(const struct tex_field *f, double u, double v)
{
    float id;
    f->prim->eval2(f, 1, &u, &v, &id);
    return (int)id;
}

/* eval2 for a primitive NAME with NAME_id(p, k, x, y): x right and y up in
 * the cell, origin at its lower-left corner (the thesis's corner convention;
 * the centred figures subtract 0.5). */
#define GEO_EVAL2(name, S)                                                                         \
    static void name##_eval2(const struct tex_field *f, int n, const double *u, const double *v,  \
                             float *out)                                                           \
    {                                                                                              \
        const S *p = f->params;                                                                    \
        const struct geo_state *s = f->state;                                                      \
        for (int i = 0; i < n; i++)                                                                \
            out[i] = (float)name##_id(p, s->k, cell(u[i] - s->du, p->nu),                         \
                                      1.0 - cell(v[i] + s->dv, p->nv));                            \
    }

/* box2 (prim.h): the one region of a box of points, or 0 when unsure.
 *
 * The rule: a box is one region when it lies inside one repetition cell and
 * every edge of the figure is farther from it than the box reaches.  Each
 * primitive bounds that from its own geometry (a distance to a circle or
 * line, an angle or a monotone function over the box), so that thin rings,
 * lines and mortar, sharp points and cusps cannot hide between samples: no
 * point of the box is skipped, whatever the feature's size.  The box is
 * widened by GEO_EPS, in cell units: far above the rounding of the id tests
 * (about 1e-12 of a cell, 1e-9 near the cycloid's cusps) and below a
 * subsample's spacing (at least 1/262144 of a cell), so that every point of a
 * box called one region (a subsample, or a pixel's centre for --ids, whose
 * boxes are one row: hv = 0) evaluates to it, bit for bit as eval2 does.  The
 * margin needs no lattice: it holds for any point of the box. */
#define GEO_EPS 1e-7

/* The box u +- hu, v +- hv in a cell (moved by the centre's shift s->du, s->dv): its centre
 * (x, y), y up as in eval2, and its half sides hx, hy widened by GEO_EPS; 0 when it reaches
 * a cell's side. */
static inline int geo_box(const struct geo_state *s, int nu, int nv, double u, double v,
                          double hu, double hv, double *x, double *y, double *hx, double *hy)
{
    *x = cell(u - s->du, nu);
    *y = 1.0 - cell(v + s->dv, nv);
    *hx = hu * nu + GEO_EPS;
    *hy = hv * nv + GEO_EPS;
    return *x - *hx > 0 && *x + *hx < 1 && *y - *hy > 0 && *y + *hy < 1;
}

/* box2 for a primitive NAME with NAME_box(p, k, x, y, hx, hy), the one region
 * of the box (x +- hx, y +- hy) inside a cell, or 0. */
#define GEO_BOX2(name, S)                                                                          \
    static void name##_box2(const struct tex_field *f, int n, const double *u, const double *v,   \
                            double hu, double hv, float *out)                                      \
    {                                                                                              \
        const S *p = f->params;                                                                    \
        double x, y, hx, hy, *k = ((struct geo_state *)f->state)->k;                              \
        for (int i = 0; i < n; i++)                                                                \
            out[i] = geo_box(f->state, p->nu, p->nv, u[i], v[i], hu, hv, &x, &y, &hx, &hy)         \
                         ? (float)name##_box(p, k, x, y, hx, hy) : 0.0f;                           \
    }

/* 1 when a disc of radius r at distance d from a circle's centre misses the circle of radius R. */
static inline int clear_of(double d, double radius, double r)
{
    return fabs(d - radius) > r;
}

/* Usage errors for parameters that depend on each other: the value va of the row of rows at
 * offset a must not exceed vb, the value at b (NOT_ABOVE: fields a and b of *p, a struct S). */
static int not_above(const struct tex_param *rows, size_t a, double va, size_t b, double vb)
{
    char na[64], nb[64];
    if (va > vb)
        return tex_usage_error("%s (%g) must not exceed %s (%g)",
                               tex_rows_option(rows, a, na, sizeof na), va,
                               tex_rows_option(rows, b, nb, sizeof nb), vb);
    return 0;
}
#define NOT_ABOVE(rows, S, p, a, b) not_above(rows, offsetof(S, a), (p)->a, offsetof(S, b), (p)->b)

/* ---- circle: 1 outside, 2 inside ---- */

struct circle_params {
    GEO_HEAD;
    double radius;
};

static const struct tex_param circle_rows[] = {
    TEX_REAL(struct circle_params, radius, 'r', 0.4, 0, 1, "R",
             "radius of the circle, in cells (0.5 touches the cell's sides)"),
    ROW_NU(struct circle_params, 1),
    ROW_NV(struct circle_params, 1),
    ROW_CENTRE(struct circle_params),
    ROW_NW(struct circle_params, 1),
    ROW_COLOR(struct circle_params, 1, PAPER, "colour of region 1, outside the circle"),
    ROW_COLOR(struct circle_params, 2, "#b8322a", "colour of region 2, inside the circle"),
    {0}};

static int circle_init(struct tex_field *f)
{
    const struct circle_params *p = f->params;
    if (geo_init(f, 2) < 0)
        return -1;
    ((struct geo_state *)f->state)->k[0] = p->radius * p->radius;
    return 0;
}

static inline int circle_id(const struct circle_params *p, const double *k, double x, double y)
{
    (void)p;
    x -= 0.5;
    y -= 0.5;
    return x * x + y * y <= k[0] ? 2 : 1;
}
GEO_EVAL2(circle, struct circle_params)

static inline int circle_box(const struct circle_params *p, const double *k, double x, double y,
                             double hx, double hy)
{
    return clear_of(hypot(x - 0.5, y - 0.5), p->radius, hypot(hx, hy)) ? circle_id(p, k, x, y) : 0;
}
GEO_BOX2(circle, struct circle_params)

static void circle_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                         const double *w, float *out)
{
    const struct circle_params *p = f->params;
    const double *k = ((const struct geo_state *)f->state)->k;
    for (int i = 0; i < n; i++) {
        double x = cell3(u[i], p->nu) - 0.5, y = cell3(v[i], p->nv) - 0.5, z = cell3(w[i], p->nw) - 0.5;
        out[i] = x * x + y * y + z * z <= k[0] ? 2.0f : 1.0f;
    }
}

const struct tex_primitive tex_prim_circle = {
    .name = "circle",
    .summary = "a circle (a ball as a solid texture): 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct circle_params),
    .params = circle_rows,
    .init = circle_init,
    .fini = geo_fini,
    .eval2 = circle_eval2,
    .box2 = circle_box2,
    .eval3 = circle_eval3,
};

/* ---- ring: 1 outside, 2 the ring, 3 inside ---- */

struct ring_params {
    GEO_HEAD;
    double radius, width;
};

static const struct tex_param ring_rows[] = {
    TEX_REAL(struct ring_params, radius, 'r', 0.4, 0, 1, "R",
             "radius of the outer circle, in cells (the thesis's r)"),
    TEX_REAL_N("ring_width", struct ring_params, width, 0, 0.12, 0, 1, "D",
               "width of the ring (the thesis's d), at most the radius", .old = "-d width"),
    ROW_NU(struct ring_params, 1),
    ROW_NV(struct ring_params, 1),
    ROW_CENTRE(struct ring_params),
    ROW_NW(struct ring_params, 1),
    ROW_COLOR(struct ring_params, 1, PAPER, "colour of region 1, outside the ring"),
    ROW_COLOR(struct ring_params, 2, INK, "colour of region 2, the ring"),
    ROW_COLOR(struct ring_params, 3, OCHRE, "colour of region 3, inside the ring"),
    {0}};

static int ring_init(struct tex_field *f)
{
    const struct ring_params *p = f->params;
    double *k;
    if (NOT_ABOVE(ring_rows, struct ring_params, p, width, radius) < 0 || geo_init(f, 3) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = p->radius * p->radius;
    /* d = r leaves no inside: not even the centre point. */
    k[1] = p->width < p->radius ? (p->radius - p->width) * (p->radius - p->width) : -1;
    return 0;
}

static inline int ring_of(const double *k, double d2)
{
    return d2 > k[0] ? 1 : d2 > k[1] ? 2 : 3;
}

static inline int ring_id(const struct ring_params *p, const double *k, double x, double y)
{
    (void)p;
    x -= 0.5;
    y -= 0.5;
    return ring_of(k, x * x + y * y);
}
GEO_EVAL2(ring, struct ring_params)

static inline int ring_box(const struct ring_params *p, const double *k, double x, double y,
                           double hx, double hy)
{
    double d = hypot(x - 0.5, y - 0.5), r = hypot(hx, hy);
    if (!clear_of(d, p->radius, r) || (k[1] >= 0 && !clear_of(d, p->radius - p->width, r)))
        return 0;
    return ring_id(p, k, x, y);
}
GEO_BOX2(ring, struct ring_params)

static void ring_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                       const double *w, float *out)
{
    const struct ring_params *p = f->params;
    const double *k = ((const struct geo_state *)f->state)->k;
    for (int i = 0; i < n; i++) {
        double x = cell3(u[i], p->nu) - 0.5, y = cell3(v[i], p->nv) - 0.5, z = cell3(w[i], p->nw) - 0.5;
        out[i] = (float)ring_of(k, x * x + y * y + z * z);
    }
}

const struct tex_primitive tex_prim_ring = {
    .name = "ring",
    .summary = "two concentric circles (spheres as a solid texture): 3 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct ring_params),
    .params = ring_rows,
    .init = ring_init,
    .fini = geo_fini,
    .eval2 = ring_eval2,
    .box2 = ring_box2,
    .eval3 = ring_eval3,
};

/* ---- ellipse: 1 outside, 2 the band, 3 inside ---- */

struct ellipse_params {
    GEO_HEAD;
    double major, minor, width, angle;
};

static const struct tex_param ellipse_rows[] = {
    TEX_REAL_N("semi_major", struct ellipse_params, major, 0, 0.45, 0, 1, "M",
               "semi-major axis of the outer ellipse, in cells (the thesis's M)", .alias = "M",
               .old = "-M major"),
    TEX_REAL_N("semi_minor", struct ellipse_params, minor, 0, 0.3, 0, 1, "M",
               "semi-minor axis of the outer ellipse (the thesis's m), at most M", .alias = "m",
               .old = "-m minor"),
    TEX_REAL_N("band_width", struct ellipse_params, width, 0, 0.08, 0, 1, "D",
               "width of the band (the thesis's d), at most m: the inner ellipse has semi-axes "
               "M-d, m-d", .old = "-d width"),
    TEX_REAL(struct ellipse_params, angle, 'a', 0, -360, 360, "DEG",
             "angle of the major axis with the horizontal, in degrees, counterclockwise"),
    ROW_NU(struct ellipse_params, 1),
    ROW_NV(struct ellipse_params, 1),
    ROW_CENTRE(struct ellipse_params),
    ROW_COLOR(struct ellipse_params, 1, PAPER, "colour of region 1, outside the ellipse"),
    ROW_COLOR(struct ellipse_params, 2, INK, "colour of region 2, the band"),
    ROW_COLOR(struct ellipse_params, 3, OCHRE, "colour of region 3, inside the band"),
    {0}};

static int ellipse_init(struct tex_field *f)
{
    const struct ellipse_params *p = f->params;
    double a = p->angle * M_PI / 180, c = cos(a), s = sin(a), *k;

    if (NOT_ABOVE(ellipse_rows, struct ellipse_params, p, minor, major) < 0 ||
        NOT_ABOVE(ellipse_rows, struct ellipse_params, p, width, minor) < 0)
        return -1;
    if (p->minor <= 0)
        return tex_usage_error("%s must be above 0 (got %g)",
                               TEX_OPTION(ellipse_rows, struct ellipse_params, minor), p->minor);
    if (f->tile && fmod(p->angle, 90) != 0) {
        /* A tilted ellipse is seamless only if it stays inside its cell. */
        double ex = sqrt(pow(p->major * c, 2) + pow(p->minor * s, 2));
        double ey = sqrt(pow(p->major * s, 2) + pow(p->minor * c, 2));
        if (ex > 0.5 || ey > 0.5)
            return tex_usage_error("%s needs %s a multiple of 90 or the ellipse inside its cell "
                                   "(it reaches %g x %g of 0.5 x 0.5)",
                                   TEX_FIELD_OPTION(tile),
                                   TEX_OPTION(ellipse_rows, struct ellipse_params, angle), ex, ey);
    }
    if (geo_init(f, 3) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = c;
    k[1] = s;
    k[2] = 1 / (p->major * p->major);
    k[3] = 1 / (p->minor * p->minor);
    k[4] = p->width < p->minor ? 1 / ((p->major - p->width) * (p->major - p->width)) : 0;
    k[5] = p->width < p->minor ? 1 / ((p->minor - p->width) * (p->minor - p->width)) : 0;
    return 0;
}

static inline int ellipse_id(const struct ellipse_params *p, const double *k, double x, double y)
{
    double xr, yr;
    (void)p;
    x -= 0.5;
    y -= 0.5;
    xr = x * k[0] + y * k[1];
    yr = y * k[0] - x * k[1];
    xr *= xr;
    yr *= yr;
    if (xr * k[2] + yr * k[3] > 1)
        return 1;
    return k[5] > 0 && xr * k[4] + yr * k[5] <= 1 ? 3 : 2;
}
GEO_EVAL2(ellipse, struct ellipse_params)

/* In the frame of the axes scaled by 1/M and 1/m, an ellipse is the unit
 * circle and a disc of radius r moves a point by at most r/m (m <= M): the
 * box is one region when the scaled distance is that far from 1 for each
 * ellipse. */
static inline int ellipse_box(const struct ellipse_params *p, const double *k, double x, double y,
                              double hx, double hy)
{
    double r = hypot(hx, hy), cx = x - 0.5, cy = y - 0.5;
    double xr = cx * k[0] + cy * k[1], yr = cy * k[0] - cx * k[1];
    if (fabs(sqrt(xr * xr * k[2] + yr * yr * k[3]) - 1) <= r * sqrt(k[3]))
        return 0;
    if (k[5] > 0 && fabs(sqrt(xr * xr * k[4] + yr * yr * k[5]) - 1) <= r * sqrt(k[5]))
        return 0;
    return ellipse_id(p, k, x, y);
}
GEO_BOX2(ellipse, struct ellipse_params)

const struct tex_primitive tex_prim_ellipse = {
    .name = "ellipse",
    .summary = "two concentric ellipses: 3 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct ellipse_params),
    .params = ellipse_rows,
    .init = ellipse_init,
    .fini = geo_fini,
    .eval2 = ellipse_eval2,
    .box2 = ellipse_box2,
};

/* ---- flower: the rose r = d sin(n theta); 1 ground, 2 the flower ---- */

struct flower_params {
    GEO_HEAD;
    int petals, rose;
    double length;
};

static const struct tex_param flower_rows[] = {
    TEX_INT(struct flower_params, petals, 0, 5, 1, 1000, "N",
            "number of petals (the thesis's n): the lobes where d sin(n theta) > 0",
            .old = "-n"),
    TEX_INT(struct flower_params, rose, 0, 0, 0, 1000, "N",
            "draw the whole rose r = d sin(n theta) instead, n petals for odd n and 2n for even "
            "n (0: use --petals)"),
    TEX_REAL_N("petal_length", struct flower_params, length, 0, 0.45, 0, 1, "D",
               "length of the petals, in cells (the thesis's d, the rose's a)", .old = "-d length"),
    ROW_NU(struct flower_params, 1),
    ROW_NV(struct flower_params, 1),
    ROW_CENTRE(struct flower_params),
    ROW_COLOR(struct flower_params, 1, "#1f4d2b", "colour of region 1, the ground"),
    ROW_COLOR(struct flower_params, 2, GOLD, "colour of region 2, the flower"),
    {0}};

static int flower_init(struct tex_field *f)
{
    const struct flower_params *p = f->params;
    /* Odd roses are mirror symmetric left-right only, and the petals alone of an even n
     * neither way: seamless while inside the cell. */
    if (f->tile && (p->rose ? p->rose % 2 : 1) && p->length > 0.5)
        return tex_usage_error(p->rose ? "%s with an odd %s needs %s at most 0.5 (got %g)"
                                       : "%s with %s needs %s at most 0.5 (got %g)",
                               TEX_FIELD_OPTION(tile),
                               p->rose ? TEX_OPTION(flower_rows, struct flower_params, rose)
                                       : TEX_OPTION(flower_rows, struct flower_params, petals),
                               TEX_OPTION(flower_rows, struct flower_params, length), p->length);
    return geo_init(f, 2);
}

/* A point at distance rho and angle theta from the centre lies on the rose
 * r = d sin(n theta) when rho <= d sin(n theta) or, through the negative half
 * of the curve drawn at theta + pi, rho <= -d sin(n theta + n pi).  For odd n
 * both say rho <= d sin(n theta) (n petals); for even n together they say
 * rho <= d |sin(n theta)| (2n petals).  --petals n keeps the first half, the n
 * lobes where sin(n theta) > 0, so that n counts the petals as the thesis means. */
static inline double flower_sin(const struct flower_params *p, double theta)
{
    int n = p->rose ? p->rose : p->petals;
    double s = sin(n * theta);
    return p->rose && n % 2 == 0 ? fabs(s) : s;
}

static inline int flower_id(const struct flower_params *p, const double *k, double x, double y)
{
    (void)k;
    x -= 0.5;
    y -= 0.5;
    return sqrt(x * x + y * y) <= p->length * flower_sin(p, atan2(y, x)) ? 2 : 1;
}
GEO_EVAL2(flower, struct flower_params)

/* A disc of radius r at distance rho > r from the centre spans rho +- r and
 * angles theta +- asin(r/rho), over which sin(n theta) (and its absolute
 * value) moves by at most n asin(r/rho). */
static inline int flower_box(const struct flower_params *p, const double *k, double x, double y,
                             double hx, double hy)
{
    double cx = x - 0.5, cy = y - 0.5, rho = hypot(cx, cy), r = hypot(hx, hy), s, ds;
    if (rho <= r)
        return 0;
    s = flower_sin(p, atan2(cy, cx));
    ds = (p->rose ? p->rose : p->petals) * asin(r / rho);
    if (rho + r < p->length * (s - ds))
        return 2;
    if (rho - r > p->length * (s + ds))
        return 1;
    (void)k;
    return 0;
}
GEO_BOX2(flower, struct flower_params)

const struct tex_primitive tex_prim_flower = {
    .name = "flower",
    .summary = "a flower, the rose curve r = d sin(n theta): 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct flower_params),
    .params = flower_rows,
    .init = flower_init,
    .fini = geo_fini,
    .eval2 = flower_eval2,
    .box2 = flower_box2,
};

/* ---- checker: 1 the top-left square's kind, 2 the other ---- */

struct checker_params {
    GEO_HEAD;
};

static const struct tex_param checker_rows[] = {
    ROW_NU(struct checker_params, 4),
    ROW_NV(struct checker_params, 4),
    ROW_CENTRE(struct checker_params),
    ROW_NW(struct checker_params, 4),
    ROW_COLOR(struct checker_params, 1, "#f0e9dc", "colour of region 1, the top-left square's kind"),
    ROW_COLOR(struct checker_params, 2, "#262626", "colour of region 2, the other squares"),
    {0}};

static int checker_init(struct tex_field *f)
{
    return geo_init(f, 2);
}

/* The cell is a 2 x 2 board: a nu x nv pattern is a 2nu x 2nv chessboard. */
static inline int checker_id(const struct checker_params *p, const double *k, double x, double y)
{
    (void)p;
    (void)k;
    return 1 + (((x >= 0.5) + (y <= 0.5)) & 1);
}
GEO_EVAL2(checker, struct checker_params)

static inline int checker_box(const struct checker_params *p, const double *k, double x, double y,
                              double hx, double hy)
{
    return fabs(x - 0.5) > hx && fabs(y - 0.5) > hy ? checker_id(p, k, x, y) : 0;
}
GEO_BOX2(checker, struct checker_params)

/* Whether s lies in the upper half of its cell, cell(s) >= 0.5 (floor(2 s) odd), with a
 * half-cell face counted in the half above it (prim/cell.h); 0 for NaN and infinities, as
 * that comparison gives. */
static inline int half_odd(double s)
{
    double c = tex_cell_floor(2 * s);
    return isfinite(c) && c - 2 * floor(c / 2) != 0;
}

static void checker_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                          const double *w, float *out)
{
    const struct checker_params *p = f->params;
    int i = 0;
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2) /* four points a vector, the same cells */
        i = tex_checker3_avx2(p->nu, p->nv, p->nw, n, u, v, w, out);
#endif
    for (; i < n; i++)
        out[i] = (float)(1 + ((half_odd(u[i] * p->nu) + half_odd(v[i] * p->nv) +
                               half_odd(w[i] * p->nw)) & 1));
}

const struct tex_primitive tex_prim_checker = {
    .name = "checker",
    .summary = "a chessboard (a 3D checker as a solid texture): 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct checker_params),
    .params = checker_rows,
    .init = checker_init,
    .fini = geo_fini,
    .eval2 = checker_eval2,
    .box2 = checker_box2,
    .eval3 = checker_eval3,
};

/* ---- stripe: 1 between the stripes, 2 the stripes ---- */

struct stripe_params {
    GEO_HEAD;
    double angle, width, spacing;
    int measured;
};

static const struct tex_param stripe_rows[] = {
    TEX_REAL(struct stripe_params, angle, 'a', 45, -360, 360, "DEG",
             "angle of the stripes with the horizontal, in degrees (the thesis's a)"),
    TEX_REAL_N("stripe_width", struct stripe_params, width, 0, 0.1, 0, 1, "L",
               "width of a stripe across it, in cells (the thesis's l)", .old = "-l width"),
    TEX_REAL(struct stripe_params, spacing, 0, 0.1, 0, 1, "D",
             "distance between neighbouring stripes, edge to edge (the thesis's d)", .old = "-d"),
    TEX_ENUM(struct stripe_params, measured, 0, "across", "across|horizontal",
             "how the width and distance are measured: across the stripes, or along the "
             "horizontal as Appendix A gives l and d"),
    ROW_NU(struct stripe_params, 1),
    ROW_NV(struct stripe_params, 1),
    ROW_CENTRE(struct stripe_params),
    ROW_COLOR(struct stripe_params, 1, PAPER, "colour of region 1, between the stripes"),
    ROW_COLOR(struct stripe_params, 2, INK, "colour of region 2, the stripes"),
    {0}};

static int stripe_init(struct tex_field *f)
{
    const struct stripe_params *p = f->params;
    double a = p->angle * M_PI / 180, *k;

    if (p->width <= 0)
        return tex_usage_error("%s must be above 0 (got %g)",
                               TEX_OPTION(stripe_rows, struct stripe_params, width), p->width);
    if (geo_init(f, 2) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = sin(a);
    k[1] = cos(a);
    /* a horizontal run of l crosses l |sin a| of the stripe */
    double across = p->measured ? fabs(k[0]) : 1;
    if (p->measured && across < 1e-9)
        return tex_usage_error("%s horizontal needs stripes that cross the horizontal (got "
                               "an angle of %g)",
                               TEX_OPTION(stripe_rows, struct stripe_params, measured), p->angle);
    k[3] = p->width * across;
    k[2] = k[3] + p->spacing * across;
    return 0;
}

/* t runs across the stripes; one stripe is centred on the cell's centre. */
static inline int stripe_id(const struct stripe_params *p, const double *k, double x, double y)
{
    double t = (x - 0.5) * k[0] - (y - 0.5) * k[1] + 0.5 * k[3], q = t / k[2];
    (void)p;
    return (q - floor(q)) * k[2] < k[3] ? 2 : 1;
}
GEO_EVAL2(stripe, struct stripe_params)

/* t moves by at most hx |sin a| + hy |cos a| over the box; the edges are
 * where t mod (width + spacing) is 0 or the width. */
static inline int stripe_box(const struct stripe_params *p, const double *k, double x, double y,
                             double hx, double hy)
{
    double t = (x - 0.5) * k[0] - (y - 0.5) * k[1] + 0.5 * k[3], q = t / k[2];
    double ph = (q - floor(q)) * k[2], r = hx * fabs(k[0]) + hy * fabs(k[1]);
    return ph > r && k[2] - ph > r && fabs(ph - k[3]) > r ? stripe_id(p, k, x, y) : 0;
}
GEO_BOX2(stripe, struct stripe_params)

const struct tex_primitive tex_prim_stripe = {
    .name = "stripe",
    .summary = "parallel stripes at an angle: 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS,
    .params_size = sizeof(struct stripe_params),
    .params = stripe_rows,
    .init = stripe_init,
    .fini = geo_fini,
    .eval2 = stripe_eval2,
    .box2 = stripe_box2,
};

/* ---- cycloid: 1 above the outer arch, 2 between the arches, 3 inside ---- */

struct cycloid_params {
    GEO_HEAD;
    double radius, width;
};

static const struct tex_param cycloid_rows[] = {
    TEX_REAL(struct cycloid_params, radius, 'r', 100, 0, 100, "PCT",
             "size of the outer arch in percent (the thesis's r): 100 spans the cell's width"),
    TEX_REAL_N("arch_width", struct cycloid_params, width, 0, 0.08, 0, 1, "D",
               "distance from the outer to the inner arch at their tops, in cells (the thesis's d)",
               .old = "-d width"),
    ROW_NU(struct cycloid_params, 1),
    ROW_NV(struct cycloid_params, 1),
    ROW_CENTRE(struct cycloid_params),
    ROW_COLOR(struct cycloid_params, 1, PAPER, "colour of region 1, above the outer arch"),
    ROW_COLOR(struct cycloid_params, 2, INK, "colour of region 2, between the arches"),
    ROW_COLOR(struct cycloid_params, 3, OCHRE, "colour of region 3, inside the inner arch"),
    {0}};

static int cycloid_init(struct tex_field *f)
{
    const struct cycloid_params *p = f->params;
    double a = p->radius / 100 / (2 * M_PI), *k;

    if (p->width > 2 * a)
        return tex_usage_error("%s (%g) must not exceed the arch's height %g (%s %g)",
                               TEX_OPTION(cycloid_rows, struct cycloid_params, width), p->width,
                               2 * a, TEX_OPTION(cycloid_rows, struct cycloid_params, radius),
                               p->radius);
    if (geo_init(f, 3) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = a;
    k[1] = a - p->width / 2;
    return 0;
}

/* Under the arch of the cycloid x = a(t - sin t), y = a(1 - cos t), its base
 * on the cell's bottom side, centred: at height y the left branch is at
 * a acos((a - y)/a) - sqrt(2ay - y^2) from the arch's start (Appendix A). */
static inline int under_arch(double a, double x, double y)
{
    double c, xl;
    if (a <= 0 || y > 2 * a)
        return 0;
    c = (a - y) / a;
    xl = a * acos(c < -1 ? -1 : c > 1 ? 1 : c) - sqrt(fmax(0, 2 * a * y - y * y));
    return fabs(x - 0.5) <= M_PI * a - xl;
}

static inline int cycloid_id(const struct cycloid_params *p, const double *k, double x, double y)
{
    (void)p;
    if (!under_arch(k[0], x, y))
        return 1;
    return under_arch(k[1], x, y) ? 3 : 2;
}
GEO_EVAL2(cycloid, struct cycloid_params)

/* The arch's half width at height y, pi a - xl(y), falls as y rises (its
 * derivative is (c - 1)/sqrt(1 - c^2) <= 0): over the box it is largest at
 * the bottom y0 and smallest at the top y1.  1: the box is under the arch,
 * -1: wholly outside it, 0: unsure. */
static int arch_box(double a, double x, double y, double hx, double hy)
{
    double y0 = y - hy, y1 = y + hy, dx = fabs(x - 0.5), dmin = dx - hx, dmax = dx + hx;
    if (a <= 0 || y0 > 2 * a)
        return -1;
    double c0 = (a - y0) / a, c1 = (a - y1) / a;
    if (dmin > M_PI * a - (a * acos(c0 < -1 ? -1 : c0) - sqrt(fmax(0, 2 * a * y0 - y0 * y0))))
        return -1;
    if (y1 <= 2 * a &&
        dmax <= M_PI * a - (a * acos(c1 < -1 ? -1 : c1) - sqrt(fmax(0, 2 * a * y1 - y1 * y1))))
        return 1;
    return 0;
}

static inline int cycloid_box(const struct cycloid_params *p, const double *k, double x, double y,
                              double hx, double hy)
{
    int outer = arch_box(k[0], x, y, hx, hy), inner;
    (void)p;
    if (outer <= 0)
        return outer < 0 ? 1 : 0;
    inner = arch_box(k[1], x, y, hx, hy);
    return inner > 0 ? 3 : inner < 0 ? 2 : 0;
}
GEO_BOX2(cycloid, struct cycloid_params)

const struct tex_primitive tex_prim_cycloid = {
    .name = "cycloid",
    .summary = "two nested cycloid arches: 3 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS,
    .params_size = sizeof(struct cycloid_params),
    .params = cycloid_rows,
    .init = cycloid_init,
    .fini = geo_fini,
    .eval2 = cycloid_eval2,
    .box2 = cycloid_box2,
};

/* ---- hypocycloid: 1 outside, 2 between the astroids, 3 inside ---- */

struct hypocycloid_params {
    GEO_HEAD;
    double radius, width;
};

static const struct tex_param hypocycloid_rows[] = {
    TEX_REAL(struct hypocycloid_params, radius, 'r', 0.45, 0, 1, "R",
             "distance from a cusp to the centre of the outer astroid, in cells (the thesis's r)"),
    TEX_REAL_N("band_width", struct hypocycloid_params, width, 0, 0.1, 0, 1, "D",
               "distance between the outer and the inner astroid (the thesis's d), at most r",
               .old = "-d width"),
    ROW_NU(struct hypocycloid_params, 1),
    ROW_NV(struct hypocycloid_params, 1),
    ROW_CENTRE(struct hypocycloid_params),
    ROW_COLOR(struct hypocycloid_params, 1, PAPER, "colour of region 1, outside"),
    ROW_COLOR(struct hypocycloid_params, 2, INK, "colour of region 2, between the astroids"),
    ROW_COLOR(struct hypocycloid_params, 3, OCHRE, "colour of region 3, inside"),
    {0}};

static int hypocycloid_init(struct tex_field *f)
{
    const struct hypocycloid_params *p = f->params;
    double *k;
    if (NOT_ABOVE(hypocycloid_rows, struct hypocycloid_params, p, width, radius) < 0 ||
        geo_init(f, 3) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = cbrt(p->radius * p->radius);
    k[1] = p->width < p->radius ? cbrt((p->radius - p->width) * (p->radius - p->width)) : -1;
    return 0;
}

/* The four-cusped hypocycloid (astroid) x^(2/3) + y^(2/3) = a^(2/3). */
static inline int hypocycloid_id(const struct hypocycloid_params *p, const double *k, double x,
                                 double y)
{
    double q;
    (void)p;
    x -= 0.5;
    y -= 0.5;
    q = cbrt(x * x) + cbrt(y * y);
    return q > k[0] ? 1 : q > k[1] ? 2 : 3;
}
GEO_EVAL2(hypocycloid, struct hypocycloid_params)

/* q grows with |x| and |y|: over the box it lies between its values at the
 * nearest and the farthest corner from the centre lines. */
static inline int hypocycloid_box(const struct hypocycloid_params *p, const double *k, double x,
                                  double y, double hx, double hy)
{
    double ax = fabs(x - 0.5), ay = fabs(y - 0.5);
    double nx = fmax(0, ax - hx), ny = fmax(0, ay - hy), fx = ax + hx, fy = ay + hy;
    double qmin = cbrt(nx * nx) + cbrt(ny * ny), qmax = cbrt(fx * fx) + cbrt(fy * fy);
    (void)p;
    if (qmin > k[0])
        return 1;
    if (qmax <= k[1])
        return 3;
    return qmin > k[1] && qmax <= k[0] ? 2 : 0;
}
GEO_BOX2(hypocycloid, struct hypocycloid_params)

const struct tex_primitive tex_prim_hypocycloid = {
    .name = "hypocycloid",
    .summary = "two nested four-cusped hypocycloids (astroids): 3 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct hypocycloid_params),
    .params = hypocycloid_rows,
    .init = hypocycloid_init,
    .fini = geo_fini,
    .eval2 = hypocycloid_eval2,
    .box2 = hypocycloid_box2,
};

/* ---- four_rings: 1 ground, 2 the rings ---- */

struct four_rings_params {
    GEO_HEAD;
    double radius, width;
};

static const struct tex_param four_rings_rows[] = {
    TEX_REAL(struct four_rings_params, radius, 'r', 0.2, 0, 0.5, "R",
             "outer radius of each ring, in cells (the thesis's r); above 0.25 they interlace"),
    TEX_REAL_N("ring_width", struct four_rings_params, width, 0, 0.06, 0, 0.5, "D",
               "width of the rings (the thesis's d), at most r", .old = "-d width"),
    ROW_NU(struct four_rings_params, 1),
    ROW_NV(struct four_rings_params, 1),
    ROW_CENTRE(struct four_rings_params),
    ROW_COLOR(struct four_rings_params, 1, PAPER, "colour of region 1, the ground"),
    ROW_COLOR(struct four_rings_params, 2, INK, "colour of region 2, the rings"),
    {0}};

static int four_rings_init(struct tex_field *f)
{
    const struct four_rings_params *p = f->params;
    double *k;
    if (NOT_ABOVE(four_rings_rows, struct four_rings_params, p, width, radius) < 0 ||
        geo_init(f, 2) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = p->radius * p->radius;
    k[1] = p->width < p->radius ? (p->radius - p->width) * (p->radius - p->width) : -1;
    return 0;
}

/* The rings of t_ring, centred in the cell's four quarters. */
static inline int four_rings_id(const struct four_rings_params *p, const double *k, double x,
                                double y)
{
    (void)p;
    for (int j = 0; j < 4; j++) {
        double dx = x - (j & 1 ? 0.75 : 0.25), dy = y - (j & 2 ? 0.75 : 0.25);
        double d2 = dx * dx + dy * dy;
        if (d2 <= k[0] && d2 > k[1])
            return 2;
    }
    return 1;
}
GEO_EVAL2(four_rings, struct four_rings_params)

static inline int four_rings_box(const struct four_rings_params *p, const double *k, double x,
                                 double y, double hx, double hy)
{
    double r = hypot(hx, hy);
    for (int j = 0; j < 4; j++) {
        double d = hypot(x - (j & 1 ? 0.75 : 0.25), y - (j & 2 ? 0.75 : 0.25));
        if (!clear_of(d, p->radius, r) || (k[1] >= 0 && !clear_of(d, p->radius - p->width, r)))
            return 0;
    }
    return four_rings_id(p, k, x, y);
}
GEO_BOX2(four_rings, struct four_rings_params)

const struct tex_primitive tex_prim_four_rings = {
    .name = "four_rings",
    .summary = "four rings, one in each quarter of the cell: 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct four_rings_params),
    .params = four_rings_rows,
    .init = four_rings_init,
    .fini = geo_fini,
    .eval2 = four_rings_eval2,
    .box2 = four_rings_box2,
};

/* ---- polygon and star: 1 outside, 2 inside ---- */

struct polygon_params {
    GEO_HEAD;
    int sides;
    double radius, inner, angle;
};

static const struct tex_param polygon_rows[] = {
    TEX_INT(struct polygon_params, sides, 0, 6, 3, 1000, "N", "number of sides", .old = "-n"),
    TEX_REAL(struct polygon_params, radius, 'r', 0.4, 0, 0.5, "R",
             "distance from a vertex to the centre, in cells"),
    TEX_REAL(struct polygon_params, angle, 'a', 90, -360, 360, "DEG",
             "direction of the first vertex, in degrees counterclockwise from the right"),
    ROW_NU(struct polygon_params, 1),
    ROW_NV(struct polygon_params, 1),
    ROW_CENTRE(struct polygon_params),
    ROW_COLOR(struct polygon_params, 1, PAPER, "colour of region 1, outside"),
    ROW_COLOR(struct polygon_params, 2, INK, "colour of region 2, inside"),
    {0}};

static const struct tex_param star_rows[] = {
    TEX_INT(struct polygon_params, sides, 0, 5, 2, 1000, "N", "number of points", .old = "-n"),
    TEX_REAL(struct polygon_params, radius, 'r', 0.45, 0, 0.5, "R",
             "distance from a point's tip to the centre, in cells"),
    TEX_REAL_N("inner_radius", struct polygon_params, inner, 0, 0.382, 0, 1, "K",
               "radius of the inner vertices as a fraction of --radius (0.382: a pentagram)",
               .old = "-i inner"),
    TEX_REAL(struct polygon_params, angle, 'a', 90, -360, 360, "DEG",
             "direction of the first point, in degrees counterclockwise from the right"),
    ROW_NU(struct polygon_params, 1),
    ROW_NV(struct polygon_params, 1),
    ROW_CENTRE(struct polygon_params),
    ROW_COLOR(struct polygon_params, 1, "#1d2a44", "colour of region 1, outside"),
    ROW_COLOR(struct polygon_params, 2, GOLD, "colour of region 2, the star"),
    {0}};

/* k: the sector angle 2 pi/n, the first vertex's angle, the outer vertex
 * A = (r, 0) and the inner one B, both in the sector's own frame. */
static int polygon_setup(struct tex_field *f, double inner_radius)
{
    const struct polygon_params *p = f->params;
    double *k;
    if (geo_init(f, 2) < 0)
        return -1;
    k = ((struct geo_state *)f->state)->k;
    k[0] = 2 * M_PI / p->sides;
    k[1] = p->angle * M_PI / 180;
    k[2] = p->radius;
    k[3] = inner_radius * cos(M_PI / p->sides);
    k[4] = inner_radius * sin(M_PI / p->sides);
    k[5] = hypot(k[3] - k[2], k[4]); /* |AB|: the edge test's value over the distance to it */
    return 0;
}

static int polygon_init(struct tex_field *f)
{
    const struct polygon_params *p = f->params;
    return polygon_setup(f, p->radius * cos(M_PI / p->sides));
}

static int star_init(struct tex_field *f)
{
    const struct polygon_params *p = f->params;
    return polygon_setup(f, p->radius * p->inner);
}

/* Fold the point into half a sector (the figure is symmetric about each
 * vertex's ray) and test it against the line through vertices A and B: the
 * value of that test, |AB| times the signed distance to the line. */
static inline double polygon_side(const double *k, double x, double y)
{
    double rho, t;
    x -= 0.5;
    y -= 0.5;
    rho = sqrt(x * x + y * y);
    t = atan2(y, x) - k[1];
    t -= k[0] * floor(t / k[0]);
    if (t > k[0] / 2)
        t = k[0] - t;
    x = rho * cos(t) - k[2];
    y = rho * sin(t);
    return (k[3] - k[2]) * y - k[4] * x;
}

static inline int polygon_id(const struct polygon_params *p, const double *k, double x, double y)
{
    (void)p;
    return polygon_side(k, x, y) >= 0 ? 2 : 1;
}
GEO_EVAL2(polygon, struct polygon_params)

/* Folding into half a sector never moves two points apart (it maps each to
 * its nearest image under the figure's symmetries), so the box's points fold
 * within hypot(hx, hy) of its centre's image, all in the half sector where
 * the only edge is the line AB. */
static inline int polygon_box(const struct polygon_params *p, const double *k, double x, double y,
                              double hx, double hy)
{
    double side = polygon_side(k, x, y);
    (void)p;
    return fabs(side) > hypot(hx, hy) * k[5] ? (side >= 0 ? 2 : 1) : 0;
}
GEO_BOX2(polygon, struct polygon_params)

const struct tex_primitive tex_prim_polygon = {
    .name = "polygon",
    .summary = "a regular polygon: 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct polygon_params),
    .params = polygon_rows,
    .init = polygon_init,
    .fini = geo_fini,
    .eval2 = polygon_eval2,
    .box2 = polygon_box2,
};

const struct tex_primitive tex_prim_star = {
    .name = "star",
    .summary = "a star with n points: 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct polygon_params),
    .params = star_rows,
    .init = star_init,
    .fini = geo_fini,
    .eval2 = polygon_eval2,
    .box2 = polygon_box2,
};

/* ---- grid: 1 the cells, 2 the lines ---- */

struct grid_params {
    GEO_HEAD;
    double width;
};

static const struct tex_param grid_rows[] = {
    TEX_REAL_N("line_width", struct grid_params, width, 0, 0.1, 0, 1, "D",
               "width of the lines as a fraction of a cell", .old = "-d width"),
    ROW_NU(struct grid_params, 8),
    ROW_NV(struct grid_params, 8),
    ROW_CENTRE(struct grid_params),
    ROW_COLOR(struct grid_params, 1, PAPER, "colour of region 1, the cells"),
    ROW_COLOR(struct grid_params, 2, "#3a3a3a", "colour of region 2, the lines"),
    {0}};

static int grid_init(struct tex_field *f)
{
    return geo_init(f, 2);
}

/* Lines run along the cells' sides, half of each in either neighbour. */
static inline int grid_id(const struct grid_params *p, const double *k, double x, double y)
{
    double h = p->width / 2;
    (void)k;
    return x < h || x >= 1 - h || y <= h || y > 1 - h ? 2 : 1;
}
GEO_EVAL2(grid, struct grid_params)

static inline int grid_box(const struct grid_params *p, const double *k, double x, double y,
                           double hx, double hy)
{
    double h = p->width / 2;
    (void)k;
    if (x + hx < h || x - hx > 1 - h || y + hy < h || y - hy > 1 - h)
        return 2;
    return x - hx > h && x + hx < 1 - h && y - hy > h && y + hy < 1 - h ? 1 : 0;
}
GEO_BOX2(grid, struct grid_params)

const struct tex_primitive tex_prim_grid = {
    .name = "grid",
    .summary = "grid lines: 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct grid_params),
    .params = grid_rows,
    .init = grid_init,
    .fini = geo_fini,
    .eval2 = grid_eval2,
    .box2 = grid_box2,
};

/* ---- brick: 1 the bricks, 2 the mortar ---- */

struct brick_params {
    GEO_HEAD;
    double width;
    int cells;
};

/* --cells numbers the bricks: at most this many repetitions (two bricks each) */
#define BRICK_CELLS_MAX 65536

static const struct tex_param brick_rows[] = {
    TEX_REAL_N("mortar_width", struct brick_params, width, 0, 0.12, 0, 1, "D",
               "width of the mortar joints as a fraction of a course's height", .old = "-d width"),
    ROW_NU(struct brick_params, 4),
    ROW_NV(struct brick_params, 4),
    ROW_CENTRE(struct brick_params),
    ROW_COLOR(struct brick_params, 1, "#a8452e", "colour of region 1, the bricks"),
    ROW_COLOR(struct brick_params, 2, "#d9d2c3", "colour of region 2, the mortar"),
    TEX_FLAG(struct brick_params, cells, 0,
             "a subregion per brick: 1 is the mortar, each brick a random id 2..2 nu nv + 1 "
             "(nu nv at most 65536), its colour1 shaded by the id, or a palette's colour"),
    {0}};

struct brick_state {
    struct geo_state g;
    float (*col)[3]; /* --cells: the colours of the mortar and of every brick id */
};

/* A cell is one brick wide and two courses high, the lower course shifted by
 * half a brick.  Joints keep one width on the map: k[0] is half the bed
 * joint in cell heights, k[1] half the head joint in cell widths. */
static int brick_init(struct tex_field *f)
{
    const struct brick_params *p = f->params;
    struct brick_state *s = calloc(1, sizeof *s);
    if (!s)
        return tex_error("out of memory");
    f->state = s;
    const float(*c)[4] = (const float(*)[4]) & p->color1;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 3; j++)
            s->g.col[k][j] = c[k][j];
    f->nregions = 2;
    f->colors = (const float(*)[3])s->g.col;
    f->nc = 1;
    s->g.du = (p->centre.v[0] - 0.5) / p->nu;
    s->g.dv = (p->centre.v[1] - 0.5) / p->nv;
    double *k = s->g.k;
    k[0] = p->width / 4;
    k[1] = p->width / 4 * p->nu / p->nv * (f->w > 0 && f->h > 0 ? (double)f->h / f->w : 1);
    if (p->cells) {
        if ((long)p->nu * p->nv > BRICK_CELLS_MAX)
            return tex_usage_error("%s numbers at most %d repetitions: nu x nv must be "
                                   "1..%d (got %d x %d)",
                                   TEX_OPTION(brick_rows, struct brick_params, cells),
                                   BRICK_CELLS_MAX, BRICK_CELLS_MAX, p->nu, p->nv);
        int n = 2 * p->nu * p->nv + 1;
        if (!(s->col = malloc(sizeof *s->col * n)))
            return tex_error("out of memory");
        for (int j = 0; j < 3; j++)
            s->col[0][j] = p->color2[j];
        for (int id = 2; id <= n; id++) /* shades of colour1, 0.75..1.25 times */
            for (int j = 0; j < 3; j++)
                s->col[id - 1][j] =
                    fminf(1, p->color1[j] * (0.75f + 0.5f * (float)(id - 2) / (float)(n - 1)));
        f->nregions = n;
        f->colors = (const float(*)[3])s->col;
    }
    return 0;
}

static void brick_fini(struct tex_field *f)
{
    struct brick_state *s = f->state;
    if (s)
        free(s->col);
    free(s);
    f->state = NULL;
}

static inline int brick_id(const struct brick_params *p, const double *k, double x, double y)
{
    (void)p;
    if (fabs(y - 0.5) < k[0] || y < k[0] || y > 1 - k[0])
        return 2;
    if (y > 0.5)
        return x < k[1] || x > 1 - k[1] ? 2 : 1;
    return fabs(x - 0.5) < k[1] ? 2 : 1;
}

/* --cells: the brick at (u, v) as a random id in 2..2 nu nv + 1, the mortar 1.  A cell's upper
 * course (y > 1/2) is brick (i, 2j), its lower course the bricks centred on its sides,
 * (i, 2j + 1) left of x = 1/2 and (i + 1, 2j + 1) right of it, i wrapping so the map tiles. */
static int brick_cell(const struct tex_field *f, const double *k, double u, double v)
{
    const struct brick_params *p = f->params;
    double su = u * p->nu, sv = v * p->nv, x = su - floor(su), y = 1.0 - (sv - floor(sv));
    if (brick_id(p, k, x, y) == 2)
        return 1;
    int64_t i = (int64_t)floor(su), j = (int64_t)floor(sv), row = 2 * j;
    if (y < 0.5) {
        row++;
        i += x >= 0.5;
    }
    i = ((i % p->nu) + p->nu) % p->nu;
    row = ((row % (2 * p->nv)) + 2 * p->nv) % (2 * p->nv);
    uint64_t h = tex_hash64(f->seed ^ tex_hash64((uint64_t)i * 0x9e3779b1u ^ (uint64_t)row));
    return 2 + (int)(h % (uint64_t)(2 * p->nu * p->nv));
}

static void brick_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    const struct brick_params *p = f->params;
    const struct geo_state *g = &((const struct brick_state *)f->state)->g;
    const double *k = g->k;
    for (int i = 0; i < n; i++)
        out[i] = p->cells ? (float)brick_cell(f, k, u[i] - g->du, v[i] + g->dv)
                          : (float)brick_id(p, k, cell(u[i] - g->du, p->nu),
                                            1.0 - cell(v[i] + g->dv, p->nv));
}

/* The mortar is axis-aligned bands: the box is one region when it lies in one
 * band, or clear of all of them and of x = 1/2 in the lower course (where
 * --cells numbers the bricks either side apart).  With --cells, inside one cell
 * and one brick, the box has its centre's brick. */
static inline int brick_box(const struct brick_params *p, const double *k, double x, double y,
                            double hx, double hy)
{
    double x0 = x - hx, x1 = x + hx, y0 = y - hy, y1 = y + hy;
    if (y1 < k[0] || y0 > 1 - k[0] || (y0 > 0.5 - k[0] && y1 < 0.5 + k[0]) ||
        (y0 > 0.5 && (x1 < k[1] || x0 > 1 - k[1])) ||
        (y1 < 0.5 && x0 > 0.5 - k[1] && x1 < 0.5 + k[1]))
        return 2;
    if (y0 > k[0] && y1 < 1 - k[0] && (y1 < 0.5 - k[0] || y0 > 0.5 + k[0]) &&
        (y0 > 0.5 ? x0 > k[1] && x1 < 1 - k[1] : x1 < 0.5 - k[1] || x0 > 0.5 + k[1]))
        return 1;
    (void)p;
    return 0;
}

static void brick_box2(const struct tex_field *f, int n, const double *u, const double *v,
                       double hu, double hv, float *out)
{
    const struct brick_params *p = f->params;
    const struct geo_state *g = &((const struct brick_state *)f->state)->g;
    const double *k = g->k;
    for (int i = 0; i < n; i++) {
        double x, y, hx, hy;
        int id = geo_box(g, p->nu, p->nv, u[i], v[i], hu, hv, &x, &y, &hx, &hy)
                     ? brick_box(p, k, x, y, hx, hy) : 0;
        if (p->cells && id)
            id = id == 2 ? 1 : brick_cell(f, k, u[i] - g->du, v[i] + g->dv);
        out[i] = (float)id;
    }
}

const struct tex_primitive tex_prim_brick = {
    .name = "brick",
    .summary = "a brick wall in running bond: 2 subregions, or one per brick",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct brick_params),
    .params = brick_rows,
    .init = brick_init,
    .fini = brick_fini,
    .eval2 = brick_eval2,
    .box2 = brick_box2,
};

/* ---- dots: 1 the ground, 2 the dots ---- */

struct dots_params {
    GEO_HEAD;
    double radius;
};

static const struct tex_param dots_rows[] = {
    TEX_REAL(struct dots_params, radius, 'r', 0.2, 0, 0.5, "R",
             "radius of the dots, in cells (they touch at 0.354)"),
    ROW_NU(struct dots_params, 4),
    ROW_NV(struct dots_params, 4),
    ROW_CENTRE(struct dots_params),
    ROW_COLOR(struct dots_params, 1, INK, "colour of region 1, the ground"),
    ROW_COLOR(struct dots_params, 2, PAPER, "colour of region 2, the dots"),
    {0}};

static int dots_init(struct tex_field *f)
{
    const struct dots_params *p = f->params;
    if (geo_init(f, 2) < 0)
        return -1;
    ((struct geo_state *)f->state)->k[0] = p->radius * p->radius;
    return 0;
}

/* Staggered polka dots: one at the cell's centre, a quarter at each corner. */
static inline int dots_id(const struct dots_params *p, const double *k, double x, double y)
{
    double cx = x - 0.5, cy = y - 0.5, ex = fmin(x, 1 - x), ey = fmin(y, 1 - y);
    (void)p;
    return cx * cx + cy * cy <= k[0] || ex * ex + ey * ey <= k[0] ? 2 : 1;
}
GEO_EVAL2(dots, struct dots_params)

/* The corner dots through the fold to the nearest corner, which never moves
 * two points apart. */
static inline int dots_box(const struct dots_params *p, const double *k, double x, double y,
                           double hx, double hy)
{
    double r = hypot(hx, hy);
    if (!clear_of(hypot(x - 0.5, y - 0.5), p->radius, r) ||
        !clear_of(hypot(fmin(x, 1 - x), fmin(y, 1 - y)), p->radius, r))
        return 0;
    return dots_id(p, k, x, y);
}
GEO_BOX2(dots, struct dots_params)

const struct tex_primitive tex_prim_dots = {
    .name = "dots",
    .summary = "staggered polka dots: 2 subregions",
    .flags = TEX_PRIM_2D | TEX_PRIM_REGIONS | TEX_PRIM_TILE,
    .params_size = sizeof(struct dots_params),
    .params = dots_rows,
    .init = dots_init,
    .fini = geo_fini,
    .eval2 = dots_eval2,
    .box2 = dots_box2,
};
