/* transform.c - area-filtered resampling: rotate, scale, shift, expand, clip */
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "ops/transform.h"

/* Background colours are given straight and stored premultiplied, like
 * the colour channels of every RGBA map. */
static void bg_layout(const float bg[4], int nc, float out[4])
{
    float a = bg[3];

    switch (nc) {
    case 1: out[0] = bg[0] * a; break;
    case 2: out[0] = bg[0]; out[1] = bg[1]; break;
    case 3: out[0] = bg[0] * a; out[1] = bg[1] * a; out[2] = bg[2] * a; break;
    default: out[0] = bg[0] * a; out[1] = bg[1] * a; out[2] = bg[2] * a; out[3] = a; break;
    }
}

void tex_sampler_init(struct tex_sampler *s, const tex_map *m, enum tex_edge edge,
                      const float bg[4])
{
    static const float black[4] = {0, 0, 0, 1};

    memset(s, 0, sizeof *s);
    s->m = m;
    s->edge = edge;
    s->nearest = m->subregions > 0;
    s->maxtaps = 32;
    s->rows = m->h;
    bg_layout(bg ? bg : black, m->nc, s->bg);
}

/* Pixel (ix,iy) through the edge rule: a pointer into the map or to bg. */
static inline const float *fetch(const struct tex_sampler *s, long ix, long iy)
{
    long x = tex_edge_index(ix, s->m->w, s->edge), y = tex_edge_index(iy, s->rows, s->edge);

    if (x < 0 || y < 0)
        return s->bg;
    y -= s->row0;
    if (y < 0 || y >= s->m->h) /* a band short of the rows it needs: its caller's error */
        return s->bg;
    return tex_map_px(s->m, (int)x, (int)y);
}

/* Huge or non-finite coordinates (from a wild warp) are pinned far outside
 * the map, where the edge rule still gives an answer. */
static inline double tame(double x)
{
    return x > -1e9 && x < 1e9 ? x : (x > 0 ? 1e9 : -1e9);
}

/* inlined into tex_sample's tap loop: a call per tap cost more than the sums */
static inline __attribute__((always_inline)) void bilinear(const struct tex_sampler *s, double x,
                                                           double y, float *out)
{
    int nc = s->m->nc;
    double fx = tame(x) - 0.5, fy = tame(y) - 0.5, x0 = floor(fx), y0 = floor(fy);
    float tx = (float)(fx - x0), ty = (float)(fy - y0);
    long ix = (long)x0, iy = (long)y0, ry = iy - s->row0;
    const float *p00, *p10, *p01, *p11;

    if (ix >= 0 && ix + 1 < s->m->w && iy >= 0 && iy + 1 < s->rows && ry >= 0 &&
        ry + 1 < s->m->h) { /* inside: the four pixels fetch() would give, without the edge rule */
        p00 = tex_map_px(s->m, (int)ix, (int)ry);
        p10 = p00 + nc;
        p01 = p00 + (size_t)s->m->w * nc;
        p11 = p01 + nc;
    } else {
        p00 = fetch(s, ix, iy);
        p10 = fetch(s, ix + 1, iy);
        p01 = fetch(s, ix, iy + 1);
        p11 = fetch(s, ix + 1, iy + 1);
    }

    if (nc == 1) { /* a grey map, the warp's usual, without the loop: the same sums */
        float a = p00[0] + (p10[0] - p00[0]) * tx, b = p01[0] + (p11[0] - p01[0]) * tx;
        out[0] = a + (b - a) * ty;
        return;
    }
    for (int c = 0; c < nc; c++) {
        float a = p00[c] + (p10[c] - p00[c]) * tx, b = p01[c] + (p11[c] - p01[c]) * tx;
        out[c] = a + (b - a) * ty;
    }
}

/* Lookups along one axis: about one per source pixel the output pixel spans,
 * so each bilinear tap covers its share; one (plain bilinear) at 1:1 and when
 * magnifying, which keeps whole-pixel lookups exact. */
static inline int taps(const double d[2], int maxtaps)
{
    double n;

    /* |a| + |b| <= 1 bounds hypot() by 1 + a few ulp, far below the 1e-6
     * that makes a second tap: one tap, as hypot() would give, at less cost. */
    if (fabs(d[0]) + fabs(d[1]) <= 1.0)
        return 1;
    /* sqrt of the squares is within a few ulp of hypot(), which costs four times more:
     * its ceiling is hypot()'s unless the length lies within 1e-9 of a whole number (or
     * overflows), where hypot() decides */
    n = sqrt(d[0] * d[0] + d[1] * d[1]) - 1e-6;
    if (!(n < 1e6 && n - floor(n) > 1e-9 && ceil(n) - n > 1e-9))
        n = hypot(d[0], d[1]) - 1e-6;
    n = ceil(n);
    return n < 1 ? 1 : n > maxtaps ? maxtaps : (int)n;
}

/* Tap i of n's offset, (i + 0.5) / n - 0.5: two taps, the usual many, at -1/4 and 1/4
 * (exactly the quotients) without a division */
static inline double offset(int i, int n)
{
    return n == 2 ? (i ? 0.25 : -0.25) : (i + 0.5) / n - 0.5;
}

void tex_sample(const struct tex_sampler *s, double x, double y, const double du[2],
                const double dv[2], float *out)
{
    int nc = s->m->nc, nu, nv, maxt = s->maxtaps > 0 ? s->maxtaps : 32;
    float acc[4] = {0, 0, 0, 0}, v[4];

    if (s->nearest) {
        const float *p = fetch(s, (long)floor(tame(x)), (long)floor(tame(y)));
        memcpy(out, p, nc * sizeof *out);
        return;
    }
    nu = taps(du, maxt);
    nv = taps(dv, maxt);
    if (nu == 1 && nv == 1) {
        bilinear(s, x, y, out);
        return;
    }
    double as[64]; /* the taps' offsets along u, divided once rather than per row */
    int once = nu <= 64;
    for (int i = 0; once && i < nu; i++)
        as[i] = offset(i, nu);
    for (int j = 0; j < nv; j++) {
        double b = offset(j, nv);
        for (int i = 0; i < nu; i++) {
            double a = once ? as[i] : offset(i, nu);
            bilinear(s, x + a * du[0] + b * dv[0], y + a * du[1] + b * dv[1], v);
            for (int c = 0; c < nc; c++)
                acc[c] += v[c];
        }
    }
    for (int c = 0; c < nc; c++)
        out[c] = acc[c] / (float)(nu * nv);
}

int tex_bg_channels(const tex_map *m, const float bg[4])
{
    return bg && bg[3] < 1.0f && m->nc != 4 ? 4 : m->nc;
}

tex_map *tex_map_channels(const tex_map *m, int nc)
{
    tex_map *r;
    size_t n = (size_t)m->w * m->h;

    if (nc == m->nc)
        return tex_map_clone(m);
    if (m->nc == 2 || nc == 2 || (m->nc == 1 && nc == 1))
        return tex_error("cannot convert %d channels to %d", m->nc, nc), NULL;
    if (!(r = tex_map_new(m->w, m->h, nc)))
        return NULL;
    if (m->history && tex_map_set_history(r, m->history) < 0) {
        tex_map_free(r);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        const float *s = m->px + i * m->nc;
        float *d = r->px + i * nc;
        if (nc == 1)
            d[0] = 0.2126f * s[0] + 0.7152f * s[1] + 0.0722f * s[2];
        else if (m->nc == 1) {
            d[0] = d[1] = d[2] = s[0];
            if (nc == 4)
                d[3] = 1.0f;
        } else {
            d[0] = s[0];
            d[1] = s[1];
            d[2] = s[2];
            if (nc == 4)
                d[3] = 1.0f;
        }
    }
    return r;
}

int tex_affine_rows(const tex_map *m, int row0, int full_h, tex_map *r, int y0,
                    const double a[6], enum tex_edge edge, const float bg[4])
{
    int nc = r->nc, w = r->w, h = r->h;
    const tex_map *src = m;
    tex_map *conv = NULL;
    struct tex_sampler s;
    const double du[2] = {a[0], a[3]}, dv[2] = {a[1], a[4]};
    /* A whole-pixel translation copies pixels: no filtering at all. */
    int exact = a[0] == 1 && a[1] == 0 && a[3] == 0 && a[4] == 1 && a[2] == floor(a[2]) &&
                a[5] == floor(a[5]);

    for (int i = 0; i < 6; i++)
        if (!isfinite(a[i]))
            return tex_usage_error("transform is not finite");
    if (nc != m->nc && !(src = conv = tex_map_channels(m, nc)))
        return -1;
    tex_sampler_init(&s, src, edge, bg);
    s.row0 = row0, s.rows = full_h;
    if (exact)
        s.nearest = 1;
#pragma omp parallel for schedule(dynamic, 4)
    for (int y = 0; y < h; y++) {
        float *row = tex_map_row(r, y);
        double Y = y0 + y + 0.5;
        for (int x = 0; x < w; x++) {
            double X = x + 0.5;
            tex_sample(&s, a[0] * X + a[1] * Y + a[2], a[3] * X + a[4] * Y + a[5], du, dv,
                       row + (size_t)x * nc);
        }
    }
    tex_map_free(conv);
    return 0;
}

tex_map *tex_affine(const tex_map *m, int w, int h, const double a[6], enum tex_edge edge,
                    const float bg[4])
{
    tex_map *r = tex_map_new(w, h, tex_bg_channels(m, bg));

    if (!r)
        return NULL;
    r->subregions = m->subregions;
    if ((m->history && tex_map_set_history(r, m->history) < 0) ||
        tex_affine_rows(m, 0, m->h, r, 0, a, edge, bg) < 0) {
        tex_map_free(r);
        return NULL;
    }
    return r;
}

void tex_affine_reads(const double a[6], int w, int y, int n, long *from, long *to)
{
    /* pixel centres' source rows at the band's corners, the lookups spread over the
     * footprint (half of |a3| + |a4| each way), the bilinear rows either side */
    double c[4] = {a[3] * 0.5 + a[4] * (y + 0.5), a[3] * (w - 0.5) + a[4] * (y + 0.5),
                   a[3] * 0.5 + a[4] * (y + n - 0.5), a[3] * (w - 0.5) + a[4] * (y + n - 0.5)};
    double lo = c[0], hi = c[0], spread = 0.5 * (fabs(a[3]) + fabs(a[4]));
    for (int i = 1; i < 4; i++)
        lo = c[i] < lo ? c[i] : lo, hi = c[i] > hi ? c[i] : hi;
    lo += a[5] - spread - 0.5, hi += a[5] + spread - 0.5;
    *from = (long)floor(lo > -1e9 ? lo : -1e9) - 1;
    *to = (long)floor(hi < 1e9 ? hi : 1e9) + 3;
}

tex_map *tex_step(const tex_map *m, const struct tex_xstep *st)
{
    return tex_affine(m, st->w, st->h, st->a, st->edge, st->bg);
}

int tex_rotate_step(int w, int h, double degrees, double cx, double cy, const float bg[4],
                    struct tex_xstep *st)
{
    double t = degrees * M_PI / 180.0, c = cos(t), s = sin(t);
    /* Output point P samples the source at c + R(-t)(P - c), with y downwards. */
    *st = (struct tex_xstep){w, h, {c, -s, cx - c * cx + s * cy, s, c, cy - s * cx - c * cy},
                             TEX_EDGE_BACKGROUND, bg};
    if (!isfinite(degrees) || !isfinite(cx) || !isfinite(cy))
        return tex_usage_error("rotation is not finite");
    return 0;
}

int tex_resize_step(int w, int h, int ow, int oh, struct tex_xstep *st)
{
    *st = (struct tex_xstep){ow, oh, {(double)w / ow, 0, 0, 0, (double)h / oh, 0},
                             TEX_EDGE_CLAMP, NULL};
    return tex_map_check_sides(ow, oh, 1);
}

int tex_scale_step(int w, int h, double sx, double sy, struct tex_xstep *st)
{
    double ow = floor(w * sx + 0.5), oh = floor(h * sy + 0.5);

    if (!(sx > 0 && sy > 0) || !(ow >= 1 && oh >= 1 && ow <= TEX_MAP_MAX_SIDE &&
                                  oh <= TEX_MAP_MAX_SIDE))
        return tex_usage_error("scale %g,%g of a %dx%d map gives %.0fx%.0f: each side must be "
                               "1..%d", sx, sy, w, h, ow, oh, TEX_MAP_MAX_SIDE);
    return tex_resize_step(w, h, (int)ow, (int)oh, st);
}

void tex_shift_step(int w, int h, double dx, double dy, int wrap, const float bg[4],
                    struct tex_xstep *st)
{
    *st = (struct tex_xstep){w, h, {1, 0, -dx, 0, 1, -dy},
                             wrap ? TEX_EDGE_WRAP : TEX_EDGE_BACKGROUND, bg};
}

int tex_expand_step(int w, int h, int ow, int oh, const float bg[4], struct tex_xstep *st)
{
    *st = (struct tex_xstep){ow, oh, {1, 0, (double)((w - ow) / 2), 0, 1, (double)((h - oh) / 2)},
                             TEX_EDGE_BACKGROUND, bg};
    return tex_map_check_sides(ow, oh, 4);
}

int tex_clip_step(int w, int h, int x0, int y0, int x1, int y1, struct tex_xstep *st)
{
    *st = (struct tex_xstep){x1 - x0, y1 - y0, {1, 0, x0, 0, 1, y0}, TEX_EDGE_CLAMP, NULL};
    if (x0 < 0 || y0 < 0 || x1 > w || y1 > h || x1 <= x0 || y1 <= y0)
        return tex_usage_error("clip window %d,%d to %d,%d must lie inside the %dx%d map and "
                               "not be empty", x0, y0, x1, y1, w, h);
    return 0;
}

/* A transform: its step (rc its result), then the step applied */
static tex_map *stepped(const tex_map *m, int rc, const struct tex_xstep *st)
{
    return rc < 0 ? NULL : tex_step(m, st);
}

tex_map *tex_rotate(const tex_map *m, double degrees, double cx, double cy, const float bg[4])
{
    struct tex_xstep st;
    return stepped(m, tex_rotate_step(m->w, m->h, degrees, cx, cy, bg, &st), &st);
}

tex_map *tex_resize(const tex_map *m, int w, int h)
{
    struct tex_xstep st;
    return stepped(m, tex_resize_step(m->w, m->h, w, h, &st), &st);
}

tex_map *tex_scale(const tex_map *m, double sx, double sy)
{
    struct tex_xstep st;
    return stepped(m, tex_scale_step(m->w, m->h, sx, sy, &st), &st);
}

tex_map *tex_shift(const tex_map *m, double dx, double dy, int wrap, const float bg[4])
{
    struct tex_xstep st;
    tex_shift_step(m->w, m->h, dx, dy, wrap, bg, &st);
    return tex_step(m, &st);
}

tex_map *tex_expand(const tex_map *m, int w, int h, const float bg[4])
{
    struct tex_xstep st;
    return stepped(m, tex_expand_step(m->w, m->h, w, h, bg, &st), &st);
}

tex_map *tex_clip(const tex_map *m, int x0, int y0, int x1, int y1)
{
    struct tex_xstep st;
    return stepped(m, tex_clip_step(m->w, m->h, x0, y0, x1, y1, &st), &st);
}
