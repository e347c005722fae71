/* prim.c - the primitive registry, fields, and sampling on a grid */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/nearest.h"
#include "base/progress.h"
#include "prim/prim.h"

const struct tex_primitive *const tex_primitives[] = {
#define TEX_PRIMITIVE(n) &tex_prim_##n,
#include "prim/primitives.def"
#undef TEX_PRIMITIVE
    NULL};

const char *tex_primitive_nearest(const char *name, char *buf, size_t n)
{
    struct tex_nearest nr;
    tex_nearest_init(&nr, name);
    for (int i = 0; tex_primitives[i]; i++)
        tex_nearest_try(&nr, tex_primitives[i]->name, strlen(tex_primitives[i]->name));
    if (!tex_nearest_name(&nr))
        return NULL;
    snprintf(buf, n, "%s", tex_nearest_name(&nr));
    return buf;
}

const struct tex_primitive *tex_primitive_get(const char *name)
{
    for (int i = 0; tex_primitives[i]; i++)
        if (strcmp(tex_primitives[i]->name, name) == 0)
            return tex_primitives[i];
    return NULL;
}

const struct tex_primitive *tex_primitive_find(const char *name)
{
    char known[1024], near[64];
    size_t n = 0;
    const struct tex_primitive *p = tex_primitive_get(name);

    if (p)
        return p;
    known[0] = '\0';
    for (int i = 0; tex_primitives[i] && n < sizeof known; i++)
        n += (size_t)snprintf(known + n, sizeof known - n, "%s%s", i ? ", " : "",
                              tex_primitives[i]->name);
    if (tex_primitive_nearest(name, near, sizeof near))
        tex_usage_error("unknown primitive '%s' (did you mean %s? known: %s)", name, near, known);
    else
        tex_usage_error("unknown primitive '%s' (known: %s)", name, known);
    return NULL;
}

struct tex_field *tex_field_new(const struct tex_primitive *p)
{
    struct tex_field *f = calloc(1, sizeof *f);

    if (!f || !(f->params = calloc(1, p->params_size ? p->params_size : 1))) {
        free(f);
        tex_error("out of memory");
        return NULL;
    }
    f->prim = p;
    f->nc = 1;
    if (tex_params_defaults(p->params, f->params) < 0) {
        tex_field_free(f);
        return NULL;
    }
    return f;
}

const struct tex_param tex_field_rows[] = {
    TEX_SEED_ROW(struct tex_field_opts, seed, 0, 0),
    TEX_TILE_ROW(struct tex_field_opts, tile),
    TEX_IDS_ROW(struct tex_field_opts, ids),
    TEX_INT(struct tex_field_opts, size, 0, 0, 1, TEX_MAP_MAX_SIDE, "N",
            "sample the field once on an N x N grid"),
    {0}};

const char *tex_rows_option(const struct tex_param *rows, size_t off, char *buf, size_t n)
{
    for (const struct tex_param *p = rows; p && p->name; p++)
        if (p->type != TEX_P_SPECIAL && p->off == off)
            return tex_param_option(p, buf, n);
    snprintf(buf, n, "(a parameter)"); /* no row stores it: a bug the tests would show */
    return buf;
}

int tex_field_set(struct tex_field *f, const char *name, const char *value)
{
    const struct tex_param *p = tex_param_find(f->prim->params, name);

    if (!p && (p = tex_param_find(tex_field_rows, name))) {
        struct tex_field_opts o = {(int)f->seed, f->tile, f->ids, f->size};
        if (tex_param_parse(p, &o, value, TEX_PARAM_WORD) < 0)
            return -1;
        f->seed = (uint64_t)o.seed;
        f->tile = o.tile;
        f->ids = o.ids;
        f->size = o.size;
        return 0;
    }
    if (!p) {
        char near[64];
        if (tex_param_nearest(f->prim->params, -1, name, near, sizeof near))
            return tex_usage_error("%s has no parameter '%s'; did you mean %s?", f->prim->name,
                                   name, near);
        return tex_usage_error("%s has no parameter '%s'", f->prim->name, name);
    }
    return tex_param_parse(p, f->params, value, TEX_PARAM_WORD);
}

const char *tex_field_whole(const struct tex_field *f)
{
    const struct tex_primitive *p = f->prim;

    if (!(p->flags & TEX_PRIM_GRID))
        return NULL;
    return !p->row ? "it synthesises the whole map at once" : p->whole ? p->whole(f) : NULL;
}

int tex_field_window(struct tex_field *f, int x, int y, int w, int h)
{
    const struct tex_primitive *p = f->prim;
    const char *why = tex_field_whole(f);

    if (why)
        return tex_usage_error("%s cannot make a window of its map (--window): %s", p->name, why);
    f->wx = x;
    f->wy = y;
    f->ww = w;
    f->wh = h;
    return 0;
}

int tex_field_init(struct tex_field *f, int w, int h)
{
    f->w = w;
    f->h = h;
    int rc = 0;
    if (f->tile && !(f->prim->flags & TEX_PRIM_TILE))
        rc = tex_usage_error("%s cannot tile (%s)", f->prim->name, TEX_FIELD_OPTION(tile));
    else if (f->ids && !(f->prim->flags & TEX_PRIM_REGIONS))
        rc = tex_usage_error("%s has no subregions (%s)", f->prim->name, TEX_FIELD_OPTION(ids));
    else if (f->prim->init)
        rc = f->prim->init(f);
    if (rc < 0 && f->style == TEX_PARAM_WORD)
        tex_error_in_words(); /* init's checks name options: a scene says words */
    return rc;
}

void tex_field_free(struct tex_field *f)
{
    if (!f)
        return;
    if (f->prim->fini)
        f->prim->fini(f);
    free(f->params);
    free(f);
}

/* A REGIONS field with box2 goes along a row by spans of SPAN pixels, for
 * both of its outputs; each pixel has P x P points (P = S, the stratified
 * subsamples, in colour; P = 1, the pixel's centre, with --ids).  Where box2
 * proves that the box around a span's points lies in one region, the span
 * takes that region (prove_row); a span left unsure in colour asks each of
 * its pixels' boxes the same (cheaper than S x S subsamples); with --ids a
 * pixel is one point, so eval2 gives it straight away.  The rest is what
 * every pixel would get:
 *   colour: the mean of the colours of the regions hit by the S x S
 *     subsamples, in a fixed order (subsample_pixels is the one that
 *     averages), so the same bytes for any thread count.  A sum of S x S
 *     copies of one float is exact in double, so a pixel wholly inside a
 *     region gets exactly that region's colour, as a proven one does;
 *   --ids: eval2's id at the pixel's centre, the points batched; box2's
 *     proven id is that id (its box holds the centre with a margin).
 * So the bytes are those of evaluating every point, which TEXTURA_AA=full
 * does (every pixel subsampled; every centre by tex_field_sample's plain
 * loop), for the tests that compare both. */
enum {
    SPAN = 16,     /* pixels a first box2 covers */
    SS_CHUNK = 256 /* unsure pixels subsampled per eval2 call */
};

/* Scratch of one thread for rows of regions, and the rows' constant boxes. */
struct region_scratch {
    int pts;    /* P: points a pixel side */
    double hu, hv, hspan; /* box2's half sides: a pixel's points, a span's */
    double *u;  /* the points' u across the window, m->w * P */
    double *cu; /* the pixels' centres, m->w, then the spans', ns */
    double *cv; /* one v, repeated: max(ns, SPAN) */
    float *bid; /* box2's answers: max(ns, SPAN) */
    float *sid; /* colour: a row's proven regions, m->w */
    int px[SS_CHUNK];
    double *eu; /* u and v of the points of one eval2 call: S * S * SS_CHUNK each */
    float *id;
};

static int aa_full(void)
{
    const char *aa = getenv("TEXTURA_AA");
    return aa && strcmp(aa, "full") == 0;
}

/* sid[x]: the one region of pixel x's points that box2 proves, else 0; with
 * P > 1 an unsure span's pixels are asked one by one.  The short last span
 * keeps a full span's box: wider, so still a proof. */
static void prove_row(const struct tex_field *f, struct region_scratch *t, int w, double v,
                      float *sid)
{
    const int ns = (w + SPAN - 1) / SPAN;

    for (int i = 0; i < (ns > SPAN ? ns : SPAN); i++)
        t->cv[i] = v;
    f->prim->box2(f, ns, t->cu + w, t->cv, t->hspan, t->hv, t->bid);
    for (int s = 0; s < ns; s++) {
        int x0 = s * SPAN, x1 = x0 + SPAN < w ? x0 + SPAN : w;
        if (t->bid[s] == 0 && t->pts > 1)
            f->prim->box2(f, x1 - x0, t->cu + x0, t->cv, t->hu, t->hv, sid + x0);
        else
            for (int x = x0; x < x1; x++)
                sid[x] = t->bid[s];
    }
}

static void subsample_pixels(const struct tex_field *f, struct region_scratch *t, int ne,
                             const double *vv, float *out)
{
    enum { S = TEX_FIELD_SS };
    double *ev = t->eu + S * S * SS_CHUNK;
    for (int e = 0, j = 0; e < ne; e++)
        for (int sy = 0; sy < S; sy++)
            for (int sx = 0; sx < S; sx++, j++) {
                t->eu[j] = t->u[t->px[e] * S + sx];
                ev[j] = vv[sy];
            }
    f->prim->eval2(f, ne * S * S, t->eu, ev, t->id);
    for (int e = 0; e < ne; e++) {
        double acc[3] = {0, 0, 0};
        for (int j = 0; j < S * S; j++) {
            int k = (int)t->id[e * S * S + j];
            if (k >= 1 && k <= f->nregions)
                for (int c = 0; c < 3; c++)
                    acc[c] += f->colors[k - 1][c];
        }
        for (int c = 0; c < 3; c++)
            out[3 * t->px[e] + c] = (float)(acc[c] / (S * S));
    }
}

/* Pixels x0..x1-1 in the colour of region k (black outside 1..nregions, as
 * the sum of no colours). */
static void fill_region(const struct tex_field *f, float *out, int x0, int x1, int k)
{
    float c[3] = {0, 0, 0};
    if (k >= 1 && k <= f->nregions)
        for (int j = 0; j < 3; j++)
            c[j] = f->colors[k - 1][j];
    for (int x = x0; x < x1; x++)
        for (int j = 0; j < 3; j++)
            out[3 * x + j] = c[j];
}

/* Subsample pixel x, or queue it: SS_CHUNK pixels go to eval2 at once. */
static void queue_pixel(const struct tex_field *f, struct region_scratch *t, int *ne, int x,
                        const double *vv, float *out)
{
    t->px[(*ne)++] = x;
    if (*ne == SS_CHUNK) {
        subsample_pixels(f, t, *ne, vv, out);
        *ne = 0;
    }
}

/* Row out in colour: subsamples at vv[0..S-1]; every pixel subsampled when full. */
static void color_row(const struct tex_field *f, struct region_scratch *t, int w, const double *vv,
                      int full, float *out)
{
    enum { S = TEX_FIELD_SS };
    int ne = 0;

    if (full) {
        for (int x = 0; x < w; x++)
            queue_pixel(f, t, &ne, x, vv, out);
        subsample_pixels(f, t, ne, vv, out);
        return;
    }
    prove_row(f, t, w, 0.5 * (vv[0] + vv[S - 1]), t->sid);
    for (int x = 0, x1; x < w; x = x1) {
        for (x1 = x + 1; x1 < w && t->sid[x1] == t->sid[x]; x1++)
            ;
        if (t->sid[x] != 0)
            fill_region(f, out, x, x1, (int)t->sid[x]);
        else
            for (int e = x; e < x1; e++)
                queue_pixel(f, t, &ne, e, vv, out);
    }
    subsample_pixels(f, t, ne, vv, out);
}

/* Row out of ids at v: the proven ones, then eval2 at the centres of the
 * others, gathered so that one call takes up to S * S * SS_CHUNK of them. */
static void ids_row(const struct tex_field *f, struct region_scratch *t, int w, double v,
                    float *out)
{
    enum { N = TEX_FIELD_SS * TEX_FIELD_SS * SS_CHUNK };
    double *ev = t->eu + N;

    prove_row(f, t, w, v, out);
    for (int x0 = 0, x1 = 0, n; x0 < w; x0 = x1) {
        for (n = 0; x1 < w && n < N; x1++)
            if (out[x1] == 0) {
                t->eu[n] = t->u[x1];
                ev[n++] = v;
            }
        if (n == 0)
            break;
        f->prim->eval2(f, n, t->eu, ev, t->id);
        for (int x = x0, j = 0; x < x1; x++)
            if (out[x] == 0)
                out[x] = t->id[j++];
    }
}

/* Rows of a REGIONS field with box2, in colour or (f->ids) as ids. */
static int sample_regions(const struct tex_field *f, tex_map *m, int x0, int y0)
{
    enum { S = TEX_FIELD_SS };
    const int P = f->ids ? 1 : S, n = m->w * P, nfull = f->w * P, ns = (m->w + SPAN - 1) / SPAN;
    const int nv = ns > SPAN ? ns : SPAN;
    const int full = !f->prim->box2 || aa_full();
    int failed = 0;

#pragma omp parallel
    {
        struct region_scratch t = {
            .pts = P,
            .hu = (double)(P - 1) / (2.0 * P * f->w),
            .hv = (double)(P - 1) / (2.0 * P * f->h),
            .hspan = (double)(SPAN * P - 1) / (2.0 * P * f->w), /* the last span may be short */
            .u = malloc(sizeof *t.u * n),
            .cu = malloc(sizeof *t.cu * (m->w + ns + nv)),
            .bid = malloc(sizeof *t.bid * (nv + m->w)),
            .eu = malloc(sizeof *t.eu * 2 * S * S * SS_CHUNK),
            .id = malloc(sizeof *t.id * S * S * SS_CHUNK),
        };
        int bad = !t.u || !t.cu || !t.bid || !t.eu || !t.id;

        if (!bad) {
            t.cv = t.cu + m->w + ns;
            t.sid = t.bid + nv;
            /* P = 1 gives (x + 0.5) / w, bit for bit as the plain loop's centres */
            for (int i = 0; i < n; i++)
                t.u[i] = ((double)x0 * P + i + 0.5) / nfull;
            /* the centres of the pixels' points, then of the spans' */
            for (int x = 0; x < m->w; x++)
                t.cu[x] = 0.5 * (t.u[x * P] + t.u[x * P + P - 1]);
            for (int s = 0; s < ns; s++)
                t.cu[m->w + s] = t.u[s * SPAN * P] + (double)(SPAN * P - 1) / (2.0 * nfull);
        }
#pragma omp for schedule(dynamic, 4)
        for (int y = 0; y < m->h; y++) {
            double vv[S];
            if (bad) {
#pragma omp atomic write
                failed = 1;
                continue;
            }
            for (int sy = 0; sy < P; sy++)
                vv[sy] = ((double)(y0 + y) * P + sy + 0.5) / ((double)P * f->h);
            if (f->ids)
                ids_row(f, &t, m->w, vv[0], tex_map_row(m, y));
            else
                color_row(f, &t, m->w, vv, full, tex_map_row(m, y));
            tex_progress_add(1);
        }
        free(t.u);
        free(t.cu);
        free(t.bid);
        free(t.eu);
        free(t.id);
    }
    if (failed)
        return tex_error("out of memory");
    return 0;
}

/* Rows y0.. of a window through the row callback, which fills whole rows:
 * each thread fills one in its own buffer and keeps the window's columns. */
static int sample_rows(const struct tex_field *f, tex_map *m, int x0, int y0)
{
    const struct tex_primitive *p = f->prim;
    const size_t nc = (size_t)m->nc;
    int failed = 0;

    if (x0 == 0 && m->w == f->w) {
        int step = p->rows ? 2 : 1; /* rows in pairs where the primitive makes them so */
#pragma omp parallel for schedule(dynamic, 4 / step)
        for (int y = 0; y < m->h; y += step) {
            if (step == 2 && y + 1 < m->h)
                p->rows(f, y0 + y, 2, tex_map_row(m, y));
            else
                p->row(f, y0 + y, tex_map_row(m, y));
            tex_progress_add(m->h - y < step ? m->h - y : step);
        }
        return 0;
    }
#pragma omp parallel
    {
        float *row = malloc(sizeof *row * nc * (size_t)f->w);
        if (!row) {
#pragma omp atomic write
            failed = 1;
        }
#pragma omp for schedule(dynamic, 4)
        for (int y = 0; y < m->h; y++)
            if (row) {
                p->row(f, y0 + y, row);
                memcpy(tex_map_row(m, y), row + nc * x0, sizeof *row * nc * m->w);
                tex_progress_add(1);
            }
        free(row);
    }
    return failed ? tex_error("out of memory") : 0;
}

int tex_field_sample_rows(const struct tex_field *f, tex_map *m)
{
    if (!f->prim->row || m->w != f->w || m->h != f->h)
        return tex_error("%s: no rows to sample into a %dx%d map", f->prim->name, m->w, m->h);
    return sample_rows(f, m, 0, 0);
}

/* Whether the field is sampled by regions (ids, or colours from f->colors) */
static int sampled_regions(const struct tex_field *f)
{
    const struct tex_primitive *p = f->prim;
    return (p->flags & TEX_PRIM_REGIONS) && !(p->flags & TEX_PRIM_GRID) && p->eval2;
}

/* ... in colour */
static int sampled_colored(const struct tex_field *f)
{
    return sampled_regions(f) && !f->ids && f->colors;
}

int tex_field_channels(const struct tex_field *f)
{
    return sampled_colored(f) ? 3 : f->nc;
}

/* The size of the maps tex_field_sample makes: the window's, else the grid's */
static void sampled_size(const struct tex_field *f, int *w, int *h)
{
    *w = f->ww > 0 ? f->ww : f->w;
    *h = f->ww > 0 ? f->wh : f->h;
}

tex_map *tex_field_sample(const struct tex_field *f)
{
    int w, h;
    sampled_size(f, &w, &h);
    tex_map *m = tex_map_new(w, h, tex_field_channels(f));

    if (m && tex_field_sample_into(f, m) < 0) {
        tex_map_free(m);
        return NULL;
    }
    return m;
}

int tex_field_sample_into(const struct tex_field *f, tex_map *m)
{
    const struct tex_primitive *p = f->prim;
    int regions = sampled_regions(f), nc = tex_field_channels(f);
    int colored = sampled_colored(f);
    /* ids by spans, one float each, unless a row callback fills the row or
     * TEXTURA_AA=full asks for every centre */
    int spans = regions && f->ids && f->nc == 1 && p->box2 && !p->row && !aa_full();
    int window = f->ww > 0, x0 = window ? f->wx : 0, y0 = window ? f->wy : 0;
    int failed = 0, w, h;

    sampled_size(f, &w, &h);
    if (m->w != w || m->h != h || m->nc != nc)
        return tex_error("%s: a %dx%dx%d map for a %dx%dx%d field", p->name, m->w, m->h, m->nc,
                         w, h, nc);
    if (window) {
        m->x0 = x0;
        m->y0 = y0;
        m->full_w = f->w;
        m->full_h = f->h;
    }
    tex_progress_stage(1, m->h); /* what remains of the bar after the primitive's init */
    if (p->flags & TEX_PRIM_REGIONS && f->ids)
        m->subregions = f->nregions;
    if (colored || spans)
        return sample_regions(f, m, x0, y0);
    if ((p->flags & TEX_PRIM_GRID) && !window)
        return p->grid(f, m);
    if (p->row)
        return sample_rows(f, m, x0, y0);
#pragma omp parallel
    {
        double *u = malloc(2 * sizeof *u * m->w), *v = u ? u + m->w : NULL;
        if (!u) {
#pragma omp atomic write
            failed = 1;
        } else {
            for (int x = 0; x < m->w; x++)
                u[x] = (x0 + x + 0.5) / f->w;
#pragma omp for schedule(dynamic, 4)
            for (int y = 0; y < m->h; y++) {
                for (int x = 0; x < m->w; x++)
                    v[x] = (y0 + y + 0.5) / f->h;
                p->eval2(f, m->w, u, v, tex_map_row(m, y));
                tex_progress_add(1);
            }
        }
        free(u);
    }
    return failed ? tex_error("out of memory") : 0;
}
