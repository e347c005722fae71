/* t_info - describe a texture map: size, channels, statistics, metadata */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/json.h"
#include "textura.h"

struct opts {
    int json, primitives, preview;
};

static const struct tex_param rows[] = {
    TEX_FLAG(struct opts, json, 0, "print JSON instead of text"),
    TEX_ENUM(struct opts, preview, 0, "none", "none|auto|sixel|kitty",
             "draw a thumbnail (at most 256 pixels a side) in the terminal instead: sixel or "
             "the kitty graphics protocol, auto picks from the environment",
             .bare = "auto"),
    TEX_FLAG(struct opts, primitives, 0,
             "list every primitive (the tool t_NAME, the scene word NAME) with its summary, and "
             "exit"),
    {0}};

static const struct tex_tool tool = {
    "t_info", "[MAP...]", "print the size, channels, per-channel statistics, subregions and "
                          "history of each texture map",
    0, rows, 0, -1};

static const char *const chname[4][4] = {{"Y"}, {"R", "G"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};

/* A JSON string on standard output */
static void json_string(const char *s)
{
    struct tex_str b = {0};
    if (tex_json_string(&b, s) < 0) {
        tex_error("out of memory");
        tex_die();
    }
    fwrite(b.s, 1, b.n, stdout);
    free(b.s);
}

/* 0 once what was printed has reached standard output; else the message and exit 1 */
static int stdout_flushed(void)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        tex_error("standard output: write error");
        tex_die();
    }
    return 0;
}

/* Whether channel statistics s of map m found no finite sample (its figures are 0s then) */
static int none_finite(const tex_map *m, const struct tex_stats *s)
{
    return s->nonfinite == (size_t)m->w * (size_t)m->h;
}

/* Each band of a stream's rows, about 1 MiB at a time, given to use(arg, y, n, rows) */
static int each_band(tex_rows_reader *r, const char *name, const tex_map *head,
                     void (*use)(void *arg, int y, int n, const float *rows), void *arg)
{
    int rows = (int)((1L << 20) / ((long)head->w * head->nc * (long)sizeof(float)));
    rows = rows < 1 ? 1 : rows > head->h ? head->h : rows;
    float *band = malloc((size_t)rows * head->w * head->nc * sizeof *band);

    if (!band)
        return tex_error("out of memory");
    for (int y = 0; y < head->h; y += rows) {
        int n = head->h - y < rows ? head->h - y : rows;
        if (tex_rows_read(r, y, n, band, name) < 0) {
            free(band);
            return -1;
        }
        use(arg, y, n, band);
    }
    free(band);
    return 0;
}

struct stats_job {
    const tex_map *head;
    struct tex_stats_acc a[4];
};

static void stats_band(void *arg, int y, int n, const float *rows)
{
    struct stats_job *j = arg;
    (void)y;
    tex_stats_add_pixels(j->a, rows, (size_t)j->head->w, (size_t)n, j->head->nc);
}

/* The statistics of a stream's rows into st, as they pass */
static int gather_rows(tex_rows_reader *r, const char *name, const tex_map *head,
                       struct tex_stats *st)
{
    struct stats_job j = {.head = head};
    for (int k = 0; k < head->nc; k++)
        tex_stats_begin(&j.a[k]);
    if (each_band(r, name, head, stats_band, &j) < 0)
        return -1;
    for (int k = 0; k < head->nc; k++)
        tex_stats_end(&j.a[k], &st[k]);
    return 0;
}

/* A thumbnail made as the rows pass, never the map whole: the map's columns and rows split
 * evenly among its pixels (x goes to x tw / w), each pixel the mean of the finite samples
 * of its box (an area filter; 0 where none is finite). */
struct thumb {
    int w, h, tw, th, nc;
    double *sum;
    unsigned *count;
};

static void thumb_band(void *arg, int y, int n, const float *rows)
{
    struct thumb *t = arg;
    for (int i = 0; i < n; i++) {
        size_t ty = (size_t)((long long)(y + i) * t->th / t->h);
        const float *row = rows + (size_t)i * t->w * t->nc;
        for (int x = 0; x < t->w; x++) {
            size_t at = (ty * t->tw + (size_t)((long long)x * t->tw / t->w)) * t->nc;
            for (int k = 0; k < t->nc; k++) {
                float v = row[(size_t)x * t->nc + k];
                if (isfinite(v))
                    t->sum[at + k] += v, t->count[at + k]++;
            }
        }
    }
}

/* The thumbnail of the map at path, at most 256 pixels a side, drawn in the terminal (how:
 * 1 auto, 2 sixel, 3 kitty): a scanline EXR's rows as they pass, another format's whole */
static int preview(const char *path, int how)
{
    const char *name = strcmp(path, "-") ? path : "standard input";
    tex_map head, *whole = NULL, *out = NULL;
    tex_rows_reader *r = tex_map_open_rows(path, &head, &whole);
    if (!r && !whole)
        return -1;
    if (whole) /* the sizes only: whole keeps its own history */
        head = *whole;
    int side = head.w > head.h ? head.w : head.h, rc = -1;
    struct thumb t = {head.w, head.h, head.w, head.h, head.nc, NULL, NULL};
    if (side > 256) {
        t.tw = (int)((long)head.w * 256 / side), t.th = (int)((long)head.h * 256 / side);
        t.tw = t.tw > 0 ? t.tw : 1, t.th = t.th > 0 ? t.th : 1;
    }
    size_t n = (size_t)t.tw * t.th * t.nc;
    if (!(t.sum = calloc(n, sizeof *t.sum)) || !(t.count = calloc(n, sizeof *t.count)) ||
        !(out = tex_map_new(t.tw, t.th, t.nc)))
        tex_error("out of memory");
    else if (r)
        rc = each_band(r, name, &head, thumb_band, &t);
    else
        thumb_band(&t, 0, whole->h, whole->px), rc = 0;
    if (rc == 0) {
        for (size_t i = 0; i < n; i++)
            out->px[i] = t.count[i] ? (float)(t.sum[i] / t.count[i]) : 0;
        rc = tex_terminal_write(stdout, out, how == 1   ? tex_terminal_guess()
                                             : how == 2 ? TEX_TERMINAL_SIXEL
                                                        : TEX_TERMINAL_KITTY);
    }
    if (r)
        tex_rows_close(r), free(head.history);
    tex_map_free(whole);
    tex_map_free(out);
    free(t.sum);
    free(t.count);
    return rc;
}

/* The map's header into head and its statistics into st: from a scanline EXR (a pipe or a
 * file) a band of rows at a time as they pass, from anything else (another format, a tiled
 * EXR) the whole map.  The input limit holds either way (tex_map_open_rows).  NULL with
 * the error set. */
static tex_map *gather(const char *path, tex_map *head, struct tex_stats *st)
{
    const char *name = strcmp(path, "-") ? path : "standard input";
    tex_map *whole = NULL;
    tex_rows_reader *r = tex_map_open_rows(path, head, &whole);

    if (!r && !whole)
        return NULL;
    if (r) {
        int ok = gather_rows(r, name, head, st);
        tex_rows_close(r);
        if (ok < 0) { /* the next map is read after this one's error */
            free(head->history);
            return NULL;
        }
        return head;
    }
    for (int k = 0; k < whole->nc; k++)
        tex_map_stats(whole, k, &st[k]);
    *head = *whole;
    head->px = NULL, head->mapped = 0;
    whole->history = NULL;
    tex_map_free(whole);
    return head;
}

/* The report of the map at path, as text or JSON (sep: what comes before a JSON object);
 * -1 with the error set. */
static int describe(const char *path, const struct opts *o, const char *sep)
{
    tex_map head, *m;
    struct tex_stats st[4];

    if (!(m = gather(path, &head, st)))
        return -1;
    if (o->json) {
        fputs(sep, stdout);
        printf("{\"file\": ");
        json_string(strcmp(path, "-") ? path : "-");
        printf(", \"width\": %d, \"height\": %d, \"channels\": %d, \"subregions\": %d,\n", m->w,
               m->h, m->nc, m->subregions);
        printf(" \"stats\": [");
        for (int k = 0; k < m->nc; k++) {
            char f[4][32]; /* null where no sample is finite: there are no figures */
            const double v[4] = {st[k].min, st[k].max, st[k].mean, st[k].stddev};
            for (int i = 0; i < 4; i++)
                snprintf(f[i], sizeof f[i], none_finite(m, &st[k]) ? "null" : "%.9g", v[i]);
            printf("%s\n  {\"channel\": \"%s\", \"min\": %s, \"max\": %s, \"mean\": %s, "
                   "\"stddev\": %s, \"nonfinite\": %zu, \"nan\": %zu}",
                   k ? "," : "", chname[m->nc - 1][k], f[0], f[1], f[2], f[3], st[k].nonfinite,
                   st[k].nan);
        }
        printf("],\n \"history\": ");
        json_string(m->history ? m->history : "");
        printf("}");
    } else {
        printf("%s: %dx%d, %d channel%s", strcmp(path, "-") ? path : "standard input", m->w, m->h,
               m->nc, m->nc > 1 ? "s" : "");
        if (m->subregions)
            printf(", %d subregions", m->subregions);
        putchar('\n');
        for (int k = 0; k < m->nc; k++) {
            size_t nan = st[k].nan, inf = st[k].nonfinite - nan;
            if (none_finite(m, &st[k])) {
                printf("  %-2s no finite values: %zu NaN, %zu inf\n", chname[m->nc - 1][k], nan,
                       inf);
                continue;
            }
            printf("  %-2s min %-12.6g max %-12.6g mean %-12.6g stddev %.6g", chname[m->nc - 1][k],
                   st[k].min, st[k].max, st[k].mean, st[k].stddev);
            if (st[k].nonfinite)
                printf("  (%zu NaN, %zu inf)", nan, inf);
            putchar('\n');
        }
        if (m->history) {
            const char *h = m->history;
            printf("history:\n");
            while (*h) {
                const char *e = strchr(h, '\n');
                int len = e ? (int)(e - h) : (int)strlen(h);
                printf("  %.*s\n", len, h);
                h += len + (e != NULL);
            }
        }
    }
    free(m->history);
    return 0;
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), status = 0, n = 0;
    if (o.primitives) { /* from the registry: a new primitive is listed by itself */
        for (const struct tex_primitive *const *p = tex_primitives; *p; p++)
            printf("%-14s %s\n", (*p)->name, (*p)->summary);
        free(c.cmdline);
        return stdout_flushed();
    }
    char *stdin_only[] = {"-", NULL};
    char **names = i < argc ? argv + i : stdin_only;
    int several = argc - i > 1;
    tex_map_set_nonfinite(TEX_NONFINITE_KEEP, 0); /* it counts them */
    if (o.json && several)
        putchar('[');
    for (; *names; names++) { /* each map reported, a failing one in a line of its own */
        int r = o.preview ? preview(*names, o.preview)
                          : describe(*names, &o, o.json && n ? ",\n" : "");
        if (r < 0) {
            r = tex_report();
            status = status > r ? status : r;
        } else {
            n++;
        }
        fflush(stdout);
    }
    if (o.json && (several || n))
        fputs(several ? "]\n" : "\n", stdout);
    free(c.cmdline);
    stdout_flushed();
    return status;
}
