/* transform.c - area-filtered resampling: rotate, scale, shift, expand, clip */
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "base/simd.h"
#include "ops/transform.h"
#include "ops/x86/sample_x86.h"

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
    s->level = tex_simd_level();
    bg_layout(bg ? bg : black, m->nc, s->bg);
}

/* The portable lookup, and tex_sample choosing it or AVX2's (the same floats) */
#define SAMPLE_FN sample_scalar
#define SAMPLE_TARGET
#include "ops/sample_template.c"

void tex_sample(const struct tex_sampler *s, double x, double y, const double du[2],
                const double dv[2], float *out)
{
#ifdef TEX_X86
    if (s->level >= TEX_SIMD_AVX2) {
        tex_sample_avx2(s, x, y, du, dv, out);
        return;
    }
#endif
    sample_scalar(s, x, y, du, dv, out);
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

/* Output row `row` (w pixels) of a whole-pixel translation: source row sy, columns from sx0 on,
 * copied in runs.  The pixels are those the sampler's nearest lookup (fetch) gives. */
static void copy_row(const struct tex_sampler *s, long sy, long sx0, float *row, int w)
{
    int nc = s->m->nc, mw = s->m->w;
    long y = tex_edge_index(sy, s->rows, s->edge);
    const float *src = y >= 0 && y - s->row0 >= 0 && y - s->row0 < s->m->h
                           ? tex_map_row(s->m, (int)(y - s->row0))
                           : NULL;

    for (int x = 0; x < w;) {
        long sx = sx0 + x, ex = sx >= 0 && sx < mw ? sx : tex_edge_index(sx, mw, s->edge);
        /* inside, and beyond it with a wrap, the pixels run on to the map's right side */
        long run = ex == sx || s->edge == TEX_EDGE_WRAP ? mw - ex : 1;
        if (!src || ex < 0) {
            memcpy(row + (size_t)x++ * nc, s->bg, nc * sizeof *row);
            continue;
        }
        run = run < w - x ? run : w - x;
        memcpy(row + (size_t)x * nc, src + (size_t)ex * nc, (size_t)run * nc * sizeof *row);
        x += (int)run;
    }
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
    if (exact && fabs(a[2]) < 1e8 && fabs(a[5]) < 1e8 && y0 + h < 1e8 && w < 1e8) {
#pragma omp parallel for schedule(static)
        for (int y = 0; y < h; y++)
            copy_row(&s, (long)(y0 + y + a[5]), (long)a[2], tex_map_row(r, y), w);
        tex_map_free(conv);
        return 0;
    }
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
