/* t_warp - domain perturbation: displace a map's lookups by another map */
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    double amount, centre, angle;
    int isotropic, edge;
    const char *size;
};

static const struct tex_param rows[] = {
    TEX_REAL_N("displacement", struct opts, amount, 0, 0.1, -100, 100, "A",
               "displacement in texture units (map widths) per unit of BY", .old = "-a amount"),
    TEX_REAL_N("neutral", struct opts, centre, 0, 0, -1e6, 1e6, "C",
               "value of BY that displaces nothing (0.5 for a symmetric push)", .old = "centre"),
    TEX_REAL(struct opts, angle, 0, 0, -1e6, 1e6, "DEG",
             "direction of the push of a 1-channel BY, degrees counter-clockwise from u"),
    TEX_FLAG(struct opts, isotropic, 0,
             "a 1-channel BY displaces along both axes (two decorrelated lookups)"),
    TEX_ENUM(struct opts, edge, 0, "wrap", "wrap|clamp",
             "lookups of MAP outside the unit square"),
    TEX_STRING(struct opts, size, 's', NULL, "N|WxH", "size of the result (default: MAP's)"),
    {0}};

static const struct tex_tool tool = {
    "t_warp", "MAP BY",
    "domain perturbation: MAP looked up at (u,v) + amount * BY(u,v), as turbulence makes "
    "marble from stripes",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 2, 2};

/* An input's rows: held whole, or a window of them that slides down the map as the bands
 * of output do, read from a spool (the window may wrap) or from the stream itself (rows
 * beyond the edges are the edge rows, as the clamp edge rule reads them) */
struct source {
    const char *name;
    int w, h, nc, subregions;
    tex_map *whole;              /* held whole, or */
    const struct tex_spool *sp;  /* the spool, or */
    tex_rows_reader *r;          /* the stream, */
    int next;                    /* its next row */
    tex_map *rows, view;         /* the window's storage, the rows it holds */
    long top;                    /* rows top..top+n-1, counted on past the edges */
    int n, off, cap;             /* from storage row off; the storage planned */
};

/* Rows y..y+k-1 of the stream into at, the rows above them not read yet passed over (read
 * and checked, as the whole map's reader would) */
static int stream_rows(struct source *s, int y, int k, float *at)
{
    for (int from, n; s->next < y + k; s->next = from + n) {
        from = s->next; /* y, or a row above it, passed over through at */
        n = from < y ? (y - from < k ? y - from : k) : k;
        if (tex_rows_read(s->r, from, n, at, s->name) < 0 ||
            tex_rows_nonfinite(at, s->w, n, s->nc, from, s->name) < 0)
            return -1;
    }
    return 0;
}

/* Room in the storage for rows top..top+need-1 from row off: the kept rows moved to the top
 * where that makes room, else storage as tall as they need (the rare case: the storage is
 * planned a quarter taller than a window) */
static int room(struct source *s, long need)
{
    size_t row = (size_t)s->w * s->nc;

    if (s->rows && s->off + need <= s->rows->h)
        return 0;
    if (s->rows && need <= s->rows->h) {
        memmove(s->rows->px, s->rows->px + s->off * row, s->n * row * sizeof(float));
        s->off = 0;
        return 0;
    }
    long cap = need > s->cap ? need : s->cap;
    tex_map *m = tex_map_new_unset(s->w, (int)(cap > s->h && need <= s->h ? s->h : cap), s->nc);
    if (!m)
        return -1;
    if (s->n)
        memcpy(m->px, s->rows->px + s->off * row, s->n * row * sizeof(float));
    tex_map_free(s->rows);
    s->rows = m, s->off = 0;
    return 0;
}

/* The window on rows [from, to) (counted on past the edges: a spool's wrap, a stream's
 * are clamped), the rows above it let go of, into *b */
static int keep(struct source *s, long from, long to, struct tex_map_rows *b)
{
    size_t row = (size_t)s->w * s->nc;

    if (s->whole) {
        *b = (struct tex_map_rows){s->whole, 0, s->h};
        return 0;
    }
    if (s->r) {
        from = from < 0 ? 0 : from > s->h - 1 ? s->h - 1 : from;
        to = to > s->h ? s->h : to < from + 1 ? from + 1 : to;
    }
    if (s->n && from > s->top) {
        int drop = from - s->top < s->n ? (int)(from - s->top) : s->n;
        s->top += drop, s->off += drop, s->n -= drop;
    }
    if (!s->n)
        s->top = from, s->off = 0;
    long y = s->top + s->n;
    if (to > y) {
        if (room(s, to - s->top) < 0)
            return -1;
        float *at = s->rows->px + (s->off + s->n) * row;
        if (s->sp ? tex_spool_read(s->sp, y, (int)(to - y), at) < 0
                  : stream_rows(s, (int)y, (int)(to - y), at) < 0)
            return -1;
        s->n += (int)(to - y);
    }
    s->view = (tex_map){.w = s->w, .h = s->n, .nc = s->nc, .subregions = s->subregions,
                        .px = s->rows->px + s->off * row};
    *b = (struct tex_map_rows){&s->view, (int)(s->top % s->h), s->h};
    return 0;
}

/* The stream's rows below the last window read and checked, as the whole map's reader
 * reads them: a map cut short fails here too */
static int drain(struct source *s)
{
    float *buf;
    int k = s->h - s->next < 64 ? s->h - s->next : 64;

    if (!s->r || k <= 0)
        return 0;
    if (!(buf = malloc((size_t)s->w * s->nc * k * sizeof *buf)))
        return tex_error("out of memory");
    while (s->next < s->h) {
        int n = s->h - s->next < k ? s->h - s->next : k;
        if (stream_rows(s, s->next, n, buf) < 0) {
            free(buf);
            return -1;
        }
    }
    free(buf);
    return 0;
}

/* BY's range as its rows pass: each channel's least and greatest finite sample
 * (tex_stats_add_range), and whether any sample is not finite */
struct range {
    int w, nc, nonfinite;
    size_t samples; /* a channel's, passed so far */
    struct tex_stats_acc acc[4];
    double lo[4], hi[4];
};

static void take_range(void *arg, const float *px, int y, int n)
{
    struct range *g = arg;
    (void)y;
    for (int c = 0; c < g->nc; c++)
        tex_stats_add_range(&g->acc[c], px + c, (size_t)g->w, (size_t)n, g->nc);
    g->samples += (size_t)g->w * n;
}

static void range_end(struct range *g)
{
    for (int c = 0; c < g->nc; c++) {
        struct tex_stats st;
        tex_stats_end(&g->acc[c], &st);
        g->lo[c] = st.min, g->hi[c] = st.max;
        g->nonfinite |= g->acc[c].n != g->samples;
    }
}

struct job {
    struct tex_warp_opts o;
    int w, h, band, iso;
    struct range g;
    struct source m, by, by2;
};

static int warp_fill(void *arg, int y, int n, float *px)
{
    struct job *j = arg;
    for (int k; n > 0; y += k, n -= k, px += (size_t)k * j->w * j->m.nc) {
        struct tex_warp_reach re;
        struct tex_map_rows mr, br, b2r;
        tex_map out = {.w = j->w, .nc = j->m.nc, .px = px};
        k = out.h = n < j->band ? n : j->band;
        tex_warp_reads(&j->o, j->by.nc, j->g.lo, j->g.hi, j->by.h, j->m.h, j->h, y, k, &re);
        if (keep(&j->m, re.m[0], re.m[1], &mr) < 0 || keep(&j->by, re.by[0], re.by[1], &br) < 0 ||
            (j->iso && keep(&j->by2, re.by2[0], re.by2[1], &b2r) < 0) ||
            (y + k == j->h && drain(&j->m) < 0) ||
            tex_warp_rows(mr, br, j->iso ? b2r : br, &j->o, &out, y, j->h) < 0)
            return -1;
    }
    return 0;
}

/* BY read: held (whole, or rows that fit two bands) or spooled, its range taken */
static void read_by(const char *path, struct job *j, tex_map **whole, struct tex_spool *sp)
{
    tex_map head;
    tex_rows_reader *r = tex_map_open_rows(path, &head, whole);
    const char *name = strcmp(path, "-") ? path : "standard input";

    if (!r && !*whole)
        tex_die();
    if (r && head.h <= 2 * tex_cli_band_rows(head.w, head.nc))
        *whole = tex_cli_rows_whole(r, &head, name), r = NULL;
    const tex_map *m = *whole ? *whole : &head;
    j->by = (struct source){.name = name, .w = m->w, .h = m->h, .nc = m->nc, .whole = *whole};
    j->g = (struct range){.w = m->w, .nc = m->nc};
    for (int c = 0; c < 4; c++)
        tex_stats_begin(&j->g.acc[c]);
    if (*whole)
        take_range(&j->g, (*whole)->px, 0, (*whole)->h);
    else {
        if (tex_spool_rows(sp, "t_warp", r, &head, name, head.h, take_range, &j->g) < 0)
            tex_die();
        tex_rows_close(r);
        free(head.history);
        j->by.sp = sp;
    }
    range_end(&j->g);
}

/* The whole of a source read at last: from its spool, or the rest of its stream */
static tex_map *whole_of(struct source *s, tex_map *head)
{
    tex_map *m;

    if (s->whole)
        return s->whole;
    if (s->r)
        return tex_cli_rows_whole(s->r, head, s->name);
    if (!(m = tex_map_new(s->w, s->h, s->nc)) || tex_spool_read(s->sp, 0, s->h, m->px) < 0)
        tex_die();
    return m;
}

/* The warp in bands when the output takes rows and MAP and BY stream: 1 when done, 0 with
 * *m and *by read whole (the caller's to warp).  The window of MAP a band reads is its own
 * rows and the displacement's reach either side; near the whole map, MAP is read whole. */
static int stream_warp(const char *mpath, const char *bpath, const struct tex_common *c,
                       struct job *j, int w, int h, tex_map **m, tex_map **by)
{
    struct tex_spool bsp = {.fd = -1}, msp = {.fd = -1};
    struct tex_warp_reach re;
    tex_map head, *mwhole = NULL;
    int bad;

    *m = *by = NULL;
    if (!tex_cli_takes_rows(c))
        return 0;
    read_by(bpath, j, by, &bsp);
    tex_rows_reader *r = tex_map_open_rows(mpath, &head, &mwhole);
    if (!r && !mwhole)
        tex_die();
    j->m = (struct source){.name = strcmp(mpath, "-") ? mpath : "standard input", .r = r,
                           .whole = mwhole, .w = head.w, .h = head.h, .nc = head.nc,
                           .subregions = head.subregions};
    j->w = w ? w : head.w, j->h = h ? h : head.h;
    j->band = tex_cli_band_rows(j->w, head.nc);
    j->iso = j->by.nc == 1 && j->o.isotropic;
    bad = j->g.nonfinite ||
          tex_warp_reads(&j->o, j->by.nc, j->g.lo, j->g.hi, j->by.h, head.h, j->h, 0,
                         j->band, &re) < 0;
    /* a band's own rows near the whole map: no gain in bands, and nothing to say */
    int one = j->h <= j->band || (double)j->band / j->h >= 0.875;
    if (mwhole || one || bad || (re.m[1] - re.m[0]) * 8 >= head.h * 7L) {
        if (!mwhole && !one) {
            if (bad)
                tex_warning("BY is not finite: reading MAP whole");
            else
                tex_warning("the displacement reaches %ld of MAP's %d rows: reading MAP whole",
                            re.m[1] - re.m[0], head.h);
        }
        *m = whole_of(&j->m, &head);
        *by = whole_of(&j->by, NULL);
        tex_spool_close(&bsp);
        return 0;
    }
    if (j->o.edge == TEX_EDGE_WRAP) { /* the first rows look up the last */
        if (tex_spool_rows(&msp, "t_warp", r, &head, j->m.name, head.h, NULL, NULL) < 0)
            tex_die();
        tex_rows_close(r);
        j->m.r = NULL, j->m.sp = &msp;
    }
    j->m.cap = (int)((re.m[1] - re.m[0]) * 5 / 4 + 64);
    /* BY's window, or BY whole where a band's window would be all of it */
    j->by.cap = j->by2.cap = (int)((re.by[1] - re.by[0]) * 5 / 4 + 64);
    if (!j->by.whole && re.by[1] - re.by[0] >= j->by.h)
        j->by.whole = whole_of(&j->by, NULL), j->by.sp = NULL;
    j->by2 = j->by;
    tex_map out = {.w = j->w, .h = j->h, .nc = head.nc, .subregions = head.subregions,
                   .history = head.history};
    tex_cli_write_rows(&out, c, warp_fill, j);
    free(out.history);
    tex_rows_close(j->m.r);
    tex_spool_close(&msp);
    tex_spool_close(&bsp);
    tex_map_free(j->m.rows);
    tex_map_free(j->by.rows);
    tex_map_free(j->by2.rows);
    tex_map_free(j->by.whole);
    return 1;
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), w, h;
    tex_map *m, *by, *r;
    struct job j = {.band = 0};

    if (!strcmp(argv[i], "-") && !strcmp(argv[i + 1], "-"))
        tex_usage_die("standard input (-) can be read only once");
    w = h = 0;
    if (o.size && tex_parse_size(o.size, &w, &h) < 0)
        tex_usage_die("-s must be N or WxH with each side 1..%d (got '%s')", TEX_MAP_MAX_SIDE,
                      o.size);
    j.o = (struct tex_warp_opts){o.amount, o.centre, o.angle, o.isotropic,
                                 o.edge ? TEX_EDGE_CLAMP : TEX_EDGE_WRAP};
    if (stream_warp(argv[i], argv[i + 1], &c, &j, w, h, &m, &by)) {
        free(c.cmdline);
        return 0;
    }
    if (!m) { /* the output takes no rows: both read whole, as they come */
        m = tex_cli_read(argv[i]);
        by = tex_cli_read(argv[i + 1]);
    }
    if (!o.size) {
        w = m->w;
        h = m->h;
    }
    if (!(r = tex_warp(m, by, &j.o, w, h)))
        tex_die();
    tex_map_free(m);
    tex_map_free(by);
    tex_cli_write(r, &c);
    tex_map_free(r);
    free(c.cmdline);
    return 0;
}
