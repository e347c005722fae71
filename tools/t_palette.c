/* t_palette - colour a texture map through a palette, or make a palette from two colours */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/spool.h"
#include "ops/palette.h"
#include "textura.h"

struct opts {
    const char *range;
    int outside;
    const char *from, *to;
    int n;
    int space;
    int list;
};

static const struct tex_param rows[] = {
    TEX_STRING(struct opts, range, 0, "auto", "auto|MIN,MAX",
               "map values MIN..MAX onto the palette, or the map's own range"),
    TEX_ENUM(struct opts, outside, 0, "clamp", "clamp|repeat|mirror",
             "values outside the range: clamp to the ends, repeat the palette, or mirror it"),
    TEX_STRING(struct opts, from, 0, NULL, "COLOUR",
               "make a palette from this colour (#rrggbb, r,g,b[,a] or grey) to the --to colour"),
    TEX_STRING(struct opts, to, 0, NULL, "COLOUR", "the end colour of the palette made with --from"),
    TEX_INT_N("stops", struct opts, n, 0, 8, 2, 4096, "N",
              "stops of the palette made with --from/--to", .old = "-n n"),
    TEX_ENUM(struct opts, space, 0, "rgb", "rgb|oklab",
             "interpolation space of the palette made with --from/--to"),
    TEX_FLAG(struct opts, list, 0,
             "list the palettes found (with a colour swatch each on a colour terminal), and exit"),
    {0}};

static const struct tex_tool tool = {
    "t_palette", "[NAME|FILE] [MAP]",
    "colour a scalar map (or a region-id map) through a palette; with --from and --to, write a "
    "palette interpolating two colours",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS | TEX_OPT_PALETTE, rows, 0, 2};

static void die_if(int fail)
{
    if (fail)
        tex_die();
}

/* Write the palette text to path, atomically (tex_out). */
static void write_text(const tex_palette *p, const char *path)
{
    struct tex_out out;
    FILE *fp;
    int r;

    if (!path || !strcmp(path, "-")) {
        if (tex_palette_write(p, stdout) < 0) {
            tex_error("standard output: write error");
            tex_die();
        }
        return;
    }
    if (tex_out_open(&out, path) < 0) {
        tex_out_close(&out, -1);
        tex_die();
    }
    if (!(fp = fdopen(out.fd, "w"))) {
        tex_error("%s: %s", path, strerror(errno));
        tex_out_close(&out, -1);
        tex_die();
    }
    r = tex_palette_write(p, fp) < 0 ? -1 : 0;
    if (fclose(fp) != 0 && r == 0)
        r = -1;
    out.fd = -1; /* fclose closed it */
    if (r < 0)
        tex_error("%s: write error: %s", path, strerror(errno));
    if (tex_out_close(&out, r) < 0)
        tex_die();
}

/* The colour editor: n colours interpolated between two, recorded as stops. */
static void make_palette(const struct opts *o, const struct tex_common *c)
{
    float a[4], b[4];
    tex_palette *two, *p;

    if (!o->from || !o->to)
        tex_usage_die("--from and --to go together (each a colour: #rrggbb or r,g,b[,a])");
    if (tex_parse_color(o->from, a) < 0)
        tex_usage_die("--from must be a colour: #rgb, #rrggbb, #rrggbbaa, r,g,b[,a] or a grey "
                      "level in 0..1 "
                      "(got '%s')", o->from);
    if (tex_parse_color(o->to, b) < 0)
        tex_usage_die("--to must be a colour: #rgb, #rrggbb, #rrggbbaa, r,g,b[,a] or a grey "
                      "level in 0..1 "
                      "(got '%s')", o->to);
    two = tex_palette_new((enum tex_palette_space)o->space);
    p = tex_palette_new((enum tex_palette_space)o->space);
    die_if(!two || !p || tex_palette_add_stop(two, 0, a) < 0 || tex_palette_add_stop(two, 1, b) < 0);
    for (int i = 0; i < o->n; i++) {
        float t = (float)i / (float)(o->n - 1), col[4];
        tex_palette_lookup(two, t, col);
        die_if(tex_palette_add_stop(p, t, col) < 0);
    }
    write_text(p, c->output);
    tex_palette_free(two);
    tex_palette_free(p);
}

/* Does standard output show 24-bit colour?  A terminal that is not "dumb", unless
 * NO_COLOR is set (no-color.org). */
static int colour_terminal(void)
{
    const char *term = getenv("TERM");
    return isatty(1) && term && *term && strcmp(term, "dumb") && !getenv("NO_COLOR");
}

/* Every palette's name, one a line; on a colour terminal a swatch of 32 cells
 * after it, each the palette at the cell's middle. */
static void list_palettes(void)
{
    char names[8192], *save, *name;
    int swatch = colour_terminal();

    tex_palette_names(names, sizeof names);
    for (name = strtok_r(names, ", ", &save); name; name = strtok_r(NULL, ", ", &save)) {
        tex_palette *p = swatch ? tex_palette_load(name) : NULL;
        printf(p ? "%-12s" : "%s", name);
        for (int k = 0; p && k < 32; k++) {
            float c[4];
            tex_palette_lookup(p, (k + 0.5f) / 32, c);
            printf("\033[48;2;%d;%d;%dm ", (int)lrintf(255 * fminf(fmaxf(c[0], 0), 1)),
                   (int)lrintf(255 * fminf(fmaxf(c[1], 0), 1)),
                   (int)lrintf(255 * fminf(fmaxf(c[2], 0), 1)));
        }
        printf("%s\n", p ? "\033[0m" : "");
        tex_palette_free(p);
    }
}

static void parse_range(const char *s, double *lo, double *hi)
{
    char buf[128];
    char *comma;

    *lo = *hi = NAN;
    if (!strcmp(s, "auto"))
        return;
    snprintf(buf, sizeof buf, "%s", s);
    if (!(comma = strchr(buf, ',')))
        goto bad;
    *comma = '\0';
    if (tex_parse_real(buf, lo) < 0 || tex_parse_real(comma + 1, hi) < 0 || !(*lo < *hi))
        goto bad;
    return;
bad:
    tex_usage_die("--range must be auto or MIN,MAX with MIN < MAX (got '%s')", s);
}

struct colouring {
    tex_palette *p;
    double lo, hi;
    int outside;
    const char *input;
};

static tex_map *colour(tex_map *band, void *arg)
{
    const struct colouring *k = arg;
    tex_map *out = tex_palette_map(k->p, band, k->lo, k->hi, (enum tex_outside)k->outside);
    if (!out)
        tex_error_context(strcmp(k->input, "-") ? k->input : "standard input");
    tex_map_free(band);
    return out;
}

struct range {
    struct tex_stats_acc a; /* of channel 0, as tex_palette_map's automatic range */
    int w, nc;
};

static void take_range(void *arg, const float *rows, int y, int n)
{
    struct range *g = arg;
    (void)y;
    tex_stats_add_range(&g->a, rows, (size_t)g->w, (size_t)n, g->nc);
}

/* The map's own range: from a stream, in bounded memory, its rows pass to a spool (io/spool.h)
 * as their range is taken, and are coloured from there a band at a time; anything else is
 * coloured whole. */
static void colour_auto(struct colouring *k, const struct tex_common *c)
{
    const char *name = strcmp(k->input, "-") ? k->input : "standard input";
    tex_map head, *whole = NULL;
    tex_rows_reader *r = NULL;
    struct tex_spool sp;
    struct range g;
    struct tex_stats st;

    if (tex_cli_takes_rows(c)) {
        if (!(r = tex_map_open_rows(k->input, &head, &whole)) && !whole)
            tex_die();
    } else {
        whole = tex_cli_read(k->input);
    }
    if (!r) {
        tex_map *out = colour(whole, k);
        if (!out)
            tex_die();
        tex_cli_write(out, c);
        tex_map_free(out);
        return;
    }
    tex_stats_begin(&g.a);
    g.w = head.w, g.nc = head.nc;
    if (tex_spool_rows(&sp, "t_palette", r, &head, name, head.h, take_range, &g) < 0)
        tex_die();
    tex_rows_close(r);
    tex_stats_end(&g.a, &st);
    k->lo = st.min, k->hi = st.max;
    tex_cli_stream_spool(&sp, &head, c, colour, k);
    tex_spool_close(&sp);
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    /* "t_palette marble -o x.png": a leading operand is the palette's name */
    const char *first = argc > 1 && argv[1][0] != '-' ? argv[1] : NULL, *name, *input = "-";
    double lo, hi;
    tex_palette *p;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o);

    if (o.list) {
        if (i < argc)
            tex_usage_die("--list takes no operand (got '%s')", argv[i]);
        list_palettes();
        free(c.cmdline);
        return 0;
    }
    if (!o.from && !o.to && (tex_cli_given("stops") || tex_cli_given("space")))
        tex_usage_die("--stops and --space apply to a palette made with --from and --to only");
    if ((o.from || o.to) && (tex_cli_given("range") || tex_cli_given("outside")))
        tex_usage_die("--range and --outside apply to colouring a map, not to --from/--to");
    if (first && c.palette)
        tex_usage_die("a palette both as --palette and as '%s'", first);
    name = c.palette;
    if (o.from || o.to) {
        if (i < argc)
            tex_usage_die("--from/--to make a palette and take no operand (got '%s')", argv[i]);
        make_palette(&o, &c);
        free(c.cmdline);
        return 0;
    }
    if (!name) {
        if (i >= argc)
            tex_usage_die("missing palette: t_palette NAME|FILE [MAP] (e.g. marble)");
        name = argv[i++];
    }
    if (i < argc)
        input = argv[i++];
    if (i < argc)
        tex_usage_die("unexpected operand '%s'", argv[i]);
    parse_range(o.range, &lo, &hi);
    die_if(!(p = tex_palette_load(name)));
    struct colouring k = {p, lo, hi, o.outside, input};
    if (!isnan(lo)) /* a given range is per pixel: a band of rows at a time */
        tex_cli_stream(input, &c, colour, &k);
    else
        colour_auto(&k, &c);
    tex_palette_free(p);
    free(c.cmdline);
    return 0;
}
