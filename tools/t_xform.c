/* t_xform - rotate, scale, shift, expand and clip a texture map, filtered */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    double rotate;
    struct tex_reals around, scale, shift, clip;
    int wrap;
    const char *expand;
    float background[4];
};

static const struct tex_param rows[] = {
    TEX_STRING(struct opts, expand, 0, NULL, "WxH",
               "first, centre the map on a W x H canvas of the background colour"),
    TEX_REAL(struct opts, rotate, 0, 0, -1e6, 1e6, "DEG",
             "then rotate counter-clockwise by DEG degrees"),
    TEX_REALS(struct opts, around, 0, NULL, -1e6, 1e6, 2, "X,Y",
              "centre of rotation in pixels (default: the centre of the map)"),
    TEX_REALS(struct opts, scale, 0, NULL, 1e-4, 1e4, 2, "SX[,SY]",
              "then scale to round(SX W) x round(SY H) pixels, filtered"),
    TEX_REALS(struct opts, shift, 0, NULL, -1e6, 1e6, 2, "DX,DY",
              "then move the content by DX,DY pixels (right, down)"),
    TEX_FLAG(struct opts, wrap, 0, "shifted content re-enters at the opposite side"),
    TEX_REALS(struct opts, clip, 0, NULL, 0, 65536, 4, "X0,Y0,X1,Y1",
              "last, keep the window [X0,X1) x [Y0,Y1) in whole pixels"),
    TEX_COLOR(struct opts, background, 0, "#000000",
              "colour of uncovered canvas; alpha < 1 adds an alpha channel"),
    {0}};

static const struct tex_tool tool = {
    "t_xform", "[MAP]",
    "expand, rotate, scale, shift and clip a texture map (in that order), with area-filtered "
    "resampling",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 0, 1};

static void step(tex_map **m, tex_map *next)
{
    if (!next)
        tex_die();
    tex_map_free(*m);
    *m = next;
}

/* Expanding, shifting by whole pixels and clipping copy pixels: output row y comes from
 * input row y + an offset, or the background.  Such a chain goes a band of rows at a time:
 * each band through the same tex_expand, tex_shift and tex_clip arithmetic (tex_affine on
 * the band's rows, placed where the whole map has them), so the bytes are the whole map's.
 * A vertical --wrap asks for the rows from some row r down, then from the top: rows above r
 * go to an unlinked file of raw rows, read back as the bands ask, the rest stream on. */
struct xchain {
    tex_rows_reader *r;  /* the input's rows, asked for from the top, but */
    struct tex_spool sp; /* fd -1, or the file of its rows 0..sp.h-1 */
    const char *name;
    int w, h, nc, subregions;
    int expand, ew, eh, enc, ox, oy; /* the canvas, its channels, tex_expand's offsets */
    int shift, dx, dy, wrap;
    int clip, cx, cy, ow;
    const float *bg;
};

/* Input rows y..y+n-1 as a map (0 <= y, y + n <= h) */
static tex_map *input_rows(struct xchain *x, int y, int n)
{
    tex_map *m = tex_map_new(x->w, n, x->nc);

    if (!m)
        return NULL;
    m->subregions = x->subregions;
    if (x->sp.fd >= 0 && y < x->sp.h ? tex_spool_read(&x->sp, y, n, m->px) < 0
                                     : tex_rows_read(x->r, y, n, m->px, x->name) < 0 ||
                                           tex_rows_nonfinite(m->px, x->w, n, x->nc, y, x->name) < 0)
        return tex_map_free(m), NULL;
    return m;
}

/* Output rows top..top+n-1 of tex_affine (width w, a[2] = a2, no vertical scale) over a map
 * of height full whose rows a..b-1 rows(x, a, b - a) makes (maps rw wide, of rnc channels):
 * the band holds every row of top..top+n-1 the map has, so rows beyond the band are beyond
 * the map, as the whole map's affine sees them. */
static tex_map *placed(struct xchain *x, int top, int n, int full, int w, double a2,
                       tex_map *(*rows)(struct xchain *, int, int), int rw, int rnc)
{
    int from = top < 0 ? 0 : top, to = top + n > full ? full : top + n;
    double a[6] = {1, 0, a2, 0, 1, 0};
    tex_map *band = from < to ? rows(x, from, to - from) : tex_map_new(rw, 1, rnc), *out;

    if (!band)
        return NULL;
    band->subregions = x->subregions;
    /* output row j samples map row top + j, band row top + j - from; none: all beyond */
    a[5] = from < to ? top - from : -2.0 * n - 2;
    out = tex_affine(band, w, n, a, TEX_EDGE_BACKGROUND, x->bg);
    tex_map_free(band);
    return out;
}

/* Rows y..y+n-1 of the expanded canvas (the input itself without --expand) */
static tex_map *canvas_rows(struct xchain *x, int y, int n)
{
    if (!x->expand)
        return input_rows(x, y, n);
    return placed(x, y + x->oy, n, x->h, x->ew, x->ox, input_rows, x->w, x->nc);
}

/* Rows y..y+n-1 after the shift.  With a vertical wrap the canvas's rows are gathered in
 * their wrapped order (at most two runs), then shifted across with the wrap */
static tex_map *shifted_rows(struct xchain *x, int y, int n)
{
    double a[6] = {1, 0, -x->dx, 0, 1, 0};
    tex_map *band = NULL, *out;

    if (!x->shift)
        return canvas_rows(x, y, n);
    if (!x->wrap)
        return placed(x, y - x->dy, n, x->eh, x->ew, -x->dx, canvas_rows, x->ew, x->enc);
    for (int k = 0; k < n;) {
        int v = (int)((((long)y + k - x->dy) % x->eh + x->eh) % x->eh);
        int run = x->eh - v < n - k ? x->eh - v : n - k;
        tex_map *part = canvas_rows(x, v, run);
        if (!part || (!band && !(band = tex_map_new(part->w, n, part->nc)))) {
            tex_map_free(part);
            tex_map_free(band);
            return NULL;
        }
        memcpy(tex_map_row(band, k), part->px, tex_map_samples(part) * sizeof(float));
        band->subregions = part->subregions;
        tex_map_free(part);
        k += run;
    }
    out = tex_affine(band, x->ew, n, a, TEX_EDGE_WRAP, x->bg);
    tex_map_free(band);
    return out;
}

static int xchain_fill(void *arg, int y, int n, float *rows)
{
    struct xchain *x = arg;
    tex_map *s = shifted_rows(x, y + x->cy, n), *c = s;

    if (s && x->clip)
        c = tex_clip(s, x->cx, 0, x->cx + x->ow, n);
    if (!c) {
        tex_map_free(s);
        return -1;
    }
    memcpy(rows, c->px, tex_map_samples(c) * sizeof *rows);
    if (c != s)
        tex_map_free(c);
    tex_map_free(s);
    return 0;
}

/* Expand, shift and clip as a chain of bands, when the input and output stream and no
 * step resamples: 1 when done, 0 with *whole the map read whole (the caller's to do) */
static int stream_chain(const char *path, const struct opts *o, int ew, int eh,
                        const struct tex_common *c, tex_map **whole)
{
    struct xchain x = {.sp = {.fd = -1}, .bg = o->background};
    tex_map head, one = {0}, out = {0};
    float px[4] = {0};

    if (o->rotate != 0 || o->scale.n ||
        (o->shift.n && (o->shift.v[0] != floor(o->shift.v[0]) ||
                        o->shift.v[1] != floor(o->shift.v[1]) ||
                        fabs(o->shift.v[0]) > 1e6 || fabs(o->shift.v[1]) > 1e6)))
        return *whole = NULL, 0; /* it resamples: stream_steps' */
    if (!tex_cli_takes_rows(c))
        return *whole = tex_cli_read(path), 0;
    x.name = strcmp(path, "-") ? path : "standard input";
    if (!(x.r = tex_map_open_rows(path, &head, whole)))
        return *whole ? 0 : (tex_die(), 0);
    x.w = head.w, x.h = head.h, x.nc = head.nc, x.subregions = head.subregions;
    x.expand = o->expand != NULL, x.ew = x.expand ? ew : x.w, x.eh = x.expand ? eh : x.h;
    x.ox = (x.w - x.ew) / 2, x.oy = (x.h - x.eh) / 2; /* tex_expand's */
    one = (tex_map){.w = 1, .h = 1, .nc = x.nc, .px = px};
    x.enc = x.expand ? tex_bg_channels(&one, o->background) : x.nc;
    one.nc = x.enc;
    out.nc = o->shift.n ? tex_bg_channels(&one, o->background) : x.enc;
    x.shift = o->shift.n > 0, x.wrap = o->wrap;
    x.dx = x.shift ? (int)o->shift.v[0] : 0, x.dy = x.shift ? (int)o->shift.v[1] : 0;
    out.w = x.ow = x.ew, out.h = x.eh;
    if ((x.clip = o->clip.n > 0)) {
        int x0 = (int)o->clip.v[0], y0 = (int)o->clip.v[1], x1 = (int)o->clip.v[2],
            y1 = (int)o->clip.v[3];
        if (x1 > x.ew || y1 > x.eh || x1 <= x0 || y1 <= y0)
            tex_usage_die("clip window %d,%d to %d,%d must lie inside the %dx%d map and not be "
                          "empty", x0, y0, x1, y1, x.ew, x.eh);
        x.cx = x0, x.cy = y0, out.w = x.ow = x1 - x0, out.h = y1 - y0;
    }
    if (x.expand && tex_map_check_sides(x.ew, x.eh, 4) < 0)
        tex_die();
    if (x.shift && x.wrap && x.dy % x.eh != 0) {
        /* the first band's input row: the canvas's row (cy - dy) mod eh, less expand's offset */
        long first = ((x.cy - (long)x.dy) % x.eh + x.eh) % x.eh + x.oy;
        if (first > 0 && first < x.h &&
            tex_spool_rows(&x.sp, "t_xform", x.r, &head, x.name, (int)first, NULL, NULL) < 0)
            tex_die();
    }
    out.subregions = x.subregions;
    out.history = head.history;
    tex_cli_write_rows(&out, c, xchain_fill, &x);
    free(out.history);
    tex_rows_close(x.r);
    tex_spool_close(&x.sp);
    return 1;
}

/* The steps of the chain (expand, rotate, scale, shift, clip, those asked for) over a
 * w x h input, into st; their number */
static int chain_steps(const struct opts *o, int w, int h, int ew, int eh, struct tex_xstep *st)
{
    int n = 0;
    if (o->expand && tex_expand_step(w, h, ew, eh, o->background, &st[n++]) < 0)
        tex_die();
    if (n) /* the canvas */
        w = st[0].w, h = st[0].h;
    if (o->rotate != 0 && tex_rotate_step(w, h, o->rotate, o->around.n ? o->around.v[0] : w / 2.0,
                                          o->around.n ? o->around.v[1] : h / 2.0, o->background,
                                          &st[n++]) < 0)
        tex_die();
    if (o->scale.n && tex_scale_step(w, h, o->scale.v[0],
                                     o->scale.n > 1 ? o->scale.v[1] : o->scale.v[0], &st[n++]) < 0)
        tex_die();
    w = n ? st[n - 1].w : w, h = n ? st[n - 1].h : h;
    if (o->shift.n)
        tex_shift_step(w, h, o->shift.v[0], o->shift.v[1], o->wrap, o->background, &st[n++]);
    if (o->clip.n && tex_clip_step(w, h, (int)o->clip.v[0], (int)o->clip.v[1], (int)o->clip.v[2],
                                   (int)o->clip.v[3], &st[n++]) < 0)
        tex_die();
    return n;
}

/* A step of a chain that streams: the rows of its output it keeps, rows top..top + n - 1,
 * made from the rows of the step before that they read (tex_affine_reads), which that step
 * keeps in turn; the first step reads the input.  Rows are asked for from the top down, and
 * kept from row off of rows' storage: rows let go of are moved out only when room is short,
 * so each row is moved a bounded number of times. */
struct kept {
    const struct tex_xstep *st; /* NULL: the input */
    struct kept *src;
    int w, h, nc, subregions;
    tex_map *rows; /* storage for rows->h rows */
    long cap;      /* the storage's planned height */
    int off, top, n;
    tex_rows_reader *r;
    const char *name;
};

static float *kept_row(const struct kept *k, int y)
{
    return k->rows->px + (size_t)(k->off + y - k->top) * k->w * k->nc;
}

/* Room for rows up to row `to` after the kept ones: the kept rows moved to the storage's top
 * where that makes room, else storage as tall as they need; the storage is made once, as
 * tall as stream_steps planned (k->cap), so this is the rare case */
static int kept_room(struct kept *k, long to)
{
    size_t row = (size_t)k->w * k->nc;
    long need = to - k->top;
    if (k->rows && k->off + need <= k->rows->h)
        return 0;
    if (k->rows && need <= k->rows->h) {
        memmove(k->rows->px, k->rows->px + (size_t)k->off * row, (size_t)k->n * row * sizeof(float));
        k->off = 0;
        return 0;
    }
    long cap = need > k->cap ? need : k->cap;
    tex_map *m = tex_map_new_unset(k->w, (int)(cap < k->h ? cap : k->h), k->nc);
    if (!m)
        return -1;
    if (k->n)
        memcpy(m->px, kept_row(k, k->top), (size_t)k->n * row * sizeof(float));
    tex_map_free(k->rows);
    k->rows = m, k->off = 0;
    return 0;
}

/* Rows [from, to) of k's output kept, the rows above from let go; -1 with the error set.
 * Rows beyond the map are its edge rows, as the clamp edge rule reads them: at least one row
 * is kept, the nearest. */
static int keep_rows(struct kept *k, long from, long to)
{
    from = from < 0 ? 0 : from > k->h - 1 ? k->h - 1 : from;
    to = to > k->h ? k->h : to < from + 1 ? from + 1 : to;
    if (k->n && from > k->top) { /* let go of the rows above */
        int drop = from - k->top < k->n ? (int)(from - k->top) : k->n;
        k->top += drop, k->off += drop, k->n -= drop;
    }
    if (!k->n)
        k->top = (int)from, k->off = 0;
    int y = k->top + k->n, n = (int)(to - y);
    if (n <= 0)
        return 0;
    if (kept_room(k, to) < 0)
        return -1;
    float *at = kept_row(k, y);
    if (!k->st) { /* the input's rows, in order */
        if (tex_rows_read(k->r, y, n, at, k->name) < 0 ||
            tex_rows_nonfinite(at, k->w, n, k->nc, y, k->name) < 0)
            return -1;
    } else {
        long sf, sto;
        tex_affine_reads(k->st->a, k->w, y, n, &sf, &sto);
        if (keep_rows(k->src, sf, sto) < 0)
            return -1;
        struct kept *s = k->src;
        tex_map band = {.w = s->w, .h = s->n, .nc = s->nc, .subregions = s->subregions,
                        .px = kept_row(s, s->top)};
        tex_map out = {.w = k->w, .h = n, .nc = k->nc, .px = at};
        if (tex_affine_rows(&band, s->top, s->h, &out, y, k->st->a, k->st->edge, k->st->bg) < 0)
            return -1;
    }
    k->n += n;
    return 0;
}

/* Rows the last step makes at a time: 64, the writer's band, or $TEXTURA_BAND_ROWS (the
 * tests try every band height) */
static int step_rows(const struct kept *last)
{
    return getenv("TEXTURA_BAND_ROWS") ? tex_cli_band_rows(last->w, last->nc) : 64;
}

static int kept_fill(void *arg, int y, int n, float *rows)
{
    struct kept *last = arg;
    size_t row = (size_t)last->w * last->nc;
    for (int b = step_rows(last), k; n > 0; y += k, n -= k, rows += k * row) {
        k = n < b ? n : b;
        if (keep_rows(last, y, y + k) < 0)
            return -1;
        memcpy(rows, kept_row(last, y), k * row * sizeof *rows);
    }
    return 0;
}

/* A chain that resamples (rotate, scale, a shift by a fraction of a pixel), a band of rows
 * at a time, each step keeping the rows the next reads: where the output takes rows, every
 * step's source rows go down the map as its output's do (no turn past 90 degrees) and no
 * shift wraps vertically.  1 when done, 0 with *whole the map read whole (the caller's to
 * do). */
static int stream_steps(const char *path, const struct opts *o, int ew, int eh,
                        const struct tex_common *c, tex_map **whole)
{
    tex_map head;
    struct tex_xstep st[5];
    struct kept k[6] = {{0}};
    int n, ok = tex_cli_takes_rows(c) && !(o->wrap && o->shift.n && o->shift.v[1] != 0);
    if (!ok)
        return *whole = tex_cli_read(path), 0;
    if (!(k[0].r = tex_map_open_rows(path, &head, whole))) {
        if (!*whole)
            tex_die();
        return 0;
    }
    k[0].name = strcmp(path, "-") ? path : "standard input";
    n = chain_steps(o, head.w, head.h, ew, eh, st);
    for (int i = 0; i < n; i++)
        ok &= st[i].a[4] >= 0;
    if (!ok) { /* read whole after all, from the reader already open */
        *whole = tex_cli_rows_whole(k[0].r, &head, k[0].name); /* it closes the reader */
        return 0;
    }
    k[0] = (struct kept){.w = head.w, .h = head.h, .nc = head.nc, .subregions = head.subregions,
                         .r = k[0].r, .name = strcmp(path, "-") ? path : "standard input"};
    for (int i = 0; i < n; i++) {
        tex_map one = {.w = 1, .h = 1, .nc = k[i].nc};
        k[i + 1] = (struct kept){.st = &st[i], .src = &k[i], .w = st[i].w, .h = st[i].h,
                                 .nc = tex_bg_channels(&one, st[i].bg),
                                 .subregions = head.subregions};
    }
    /* each step's storage planned from the last: the rows the band after it reads, and a
     * quarter more, so the kept rows move up once every few bands */
    k[n].cap = step_rows(&k[n]);
    for (int i = n; i > 0; i--) {
        long from, to;
        tex_affine_reads(st[i - 1].a, k[i].w, 0, (int)(k[i].cap < k[i].h ? k[i].cap : k[i].h),
                         &from, &to);
        k[i - 1].cap = (to - from) + (to - from) / 4 + 64;
    }
    tex_map out = {.w = k[n].w, .h = k[n].h, .nc = k[n].nc, .subregions = head.subregions,
                   .history = head.history};
    tex_cli_write_rows(&out, c, kept_fill, &k[n]);
    free(out.history);
    tex_rows_close(k[0].r);
    for (int i = 0; i <= n; i++)
        tex_map_free(k[i].rows);
    return 1;
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), ew = 0, eh = 0;
    tex_map *m;

    if (o.expand) {
        char *e;
        long a = strtol(o.expand, &e, 10), b = a;
        if (*e == 'x' || *e == 'X')
            b = strtol(e + 1, &e, 10);
        if (*e || a < 1 || b < 1 || a > TEX_MAP_MAX_SIDE || b > TEX_MAP_MAX_SIDE)
            tex_usage_die("--expand must be N or WxH with each side 1..%d (got '%s')",
                          TEX_MAP_MAX_SIDE, o.expand);
        ew = (int)a;
        eh = (int)b;
    }
    if (o.around.n == 1)
        tex_usage_die("--around needs X,Y (got one value)");
    if (o.shift.n == 1)
        tex_usage_die("--shift needs DX,DY (got one value)");
    if (o.clip.n && o.clip.n != 4)
        tex_usage_die("--clip needs X0,Y0,X1,Y1 (got %d values)", o.clip.n);
    for (int k = 0; k < o.clip.n; k++)
        if (o.clip.v[k] != floor(o.clip.v[k]))
            tex_usage_die("--clip takes whole pixels (got %g)", o.clip.v[k]);
    const char *path = i < argc ? argv[i] : "-";
    m = NULL;
    if (stream_chain(path, &o, ew, eh, &c, &m) || (!m && stream_steps(path, &o, ew, eh, &c, &m))) {
        free(c.cmdline);
        return 0;
    }
    struct tex_xstep st[5];
    for (int k = 0, n = chain_steps(&o, m->w, m->h, ew, eh, st); k < n; k++)
        step(&m, tex_step(m, &st[k]));
    tex_cli_write(m, &c);
    tex_map_free(m);
    free(c.cmdline);
    return 0;
}
