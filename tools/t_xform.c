/* t_xform - rotate, scale, shift, expand and clip a texture map, filtered */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
 * A vertical --wrap needs the last rows first: the input goes to an unlinked file of raw
 * rows, read back as the bands ask. */
struct xchain {
    tex_rows_reader *r; /* the input's rows, asked for from the top, or */
    int spool;          /* -1, or the file of its rows */
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
    size_t row = (size_t)x->w * x->nc * sizeof(float);

    if (!m)
        return NULL;
    m->subregions = x->subregions;
    if (x->spool < 0) {
        if (tex_rows_read(x->r, y, n, m->px, x->name) < 0 ||
            tex_rows_nonfinite(m->px, x->w, n, x->nc, y, x->name) < 0)
            return tex_map_free(m), NULL;
        return m;
    }
    for (size_t done = 0, want = row * n; done < want;) {
        ssize_t k = pread(x->spool, (char *)m->px + done, want - done, (off_t)(row * y + done));
        if (k <= 0 && !(k < 0 && errno == EINTR))
            return tex_error("%s: spooled rows: %s", x->name, k < 0 ? strerror(errno) : "short"),
                   tex_map_free(m), NULL;
        done += k > 0 ? (size_t)k : 0;
    }
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

/* The input's rows into an unlinked file in TMPDIR, about 1 MiB at a time */
static void spool_input(struct xchain *x)
{
    const char *dir = getenv("TMPDIR");
    char tmp[4096];
    int rows = (int)((1L << 20) / ((long)x->w * x->nc * (long)sizeof(float)));

    snprintf(tmp, sizeof tmp, "%s/.t_xform.XXXXXX", dir && *dir ? dir : "/tmp");
    if ((x->spool = mkstemp(tmp)) < 0) {
        tex_error("%s: %s", tmp, strerror(errno));
        tex_die();
    }
    unlink(tmp);
    rows = rows < 1 ? 1 : rows;
    for (int y = 0; y < x->h; y += rows) {
        int n = x->h - y < rows ? x->h - y : rows, fd = x->spool;
        x->spool = -1;
        tex_map *m = input_rows(x, y, n);
        x->spool = fd;
        if (!m || tex_write_all(fd, m->px, tex_map_samples(m) * sizeof(float), "a spool") < 0)
            tex_die();
        tex_map_free(m);
    }
}

/* Expand, shift and clip as a chain of bands, when the input and output stream and no
 * step resamples: 1 when done, 0 with *whole the map read whole (the caller's to do) */
static int stream_chain(const char *path, const struct opts *o, int ew, int eh,
                        const struct tex_common *c, tex_map **whole)
{
    struct xchain x = {.spool = -1, .bg = o->background};
    tex_map head, one = {0}, out = {0};
    float px[4] = {0};

    if (o->rotate != 0 || o->scale.n || !tex_cli_takes_rows(c) ||
        (o->shift.n && (o->shift.v[0] != floor(o->shift.v[0]) ||
                        o->shift.v[1] != floor(o->shift.v[1]) ||
                        fabs(o->shift.v[0]) > 1e6 || fabs(o->shift.v[1]) > 1e6)))
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
    if (x.expand && tex_map_check_size(x.ew, x.eh, 4) < 0)
        tex_die();
    if (x.shift && x.wrap && x.dy % x.eh != 0)
        spool_input(&x);
    out.subregions = x.subregions;
    out.history = head.history;
    tex_cli_write_rows(&out, c, xchain_fill, &x);
    free(out.history);
    tex_rows_close(x.r);
    if (x.spool >= 0)
        close(x.spool);
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
    if (stream_chain(i < argc ? argv[i] : "-", &o, ew, eh, &c, &m)) {
        free(c.cmdline);
        return 0;
    }
    if (o.expand)
        step(&m, tex_expand(m, ew, eh, o.background));
    if (o.rotate != 0) {
        double cx = o.around.n ? o.around.v[0] : m->w / 2.0;
        double cy = o.around.n ? o.around.v[1] : m->h / 2.0;
        step(&m, tex_rotate(m, o.rotate, cx, cy, o.background));
    }
    if (o.scale.n)
        step(&m, tex_scale(m, o.scale.v[0], o.scale.n > 1 ? o.scale.v[1] : o.scale.v[0]));
    if (o.shift.n)
        step(&m, tex_shift(m, o.shift.v[0], o.shift.v[1], o.wrap, o.background));
    if (o.clip.n)
        step(&m, tex_clip(m, (int)o.clip.v[0], (int)o.clip.v[1], (int)o.clip.v[2],
                          (int)o.clip.v[3]));
    tex_cli_write(m, &c);
    tex_map_free(m);
    free(c.cmdline);
    return 0;
}
