/* cli.c - options, help, errors and the generator main for every tool */
#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli/cli.h"
#include "base/error.h"
#include "io/file.h"
#include "ops/palette.h"
#include "io/stream.h"

#ifndef TEX_VERSION
#define TEX_VERSION "0.1"
#endif

const char *tex_progname = "textura";

#define C(f) offsetof(struct tex_common, f)
/* The common options: rows over struct tex_common, each with its mask bit. */
static const struct {
    unsigned mask;
    struct tex_param row;
} common_rows[] = {
    {TEX_OPT_OUTPUT, TEX_STRING(struct tex_common, output, 'o', NULL, "FILE",
                                "write to FILE, its format from the extension (default: the EXR "
                                "stream on standard output)")},
    {TEX_OPT_OUTPUT, {"depth", 0, TEX_P_ENUM, C(depth_choice), 0, 0, 0, "auto", "auto|8|16|32", 0,
                      NULL, "bits per sample of integer formats, or 32 for float", 0, 0, 0}},
    {TEX_OPT_OUTPUT, {"compression", 0, TEX_P_ENUM, C(compression), 0, 0, 0, "zip", "none|zip|piz",
                      0, NULL, "compression of EXR files on disk (the stream is never compressed)",
                      0, 0, 0}},
    {TEX_OPT_OUTPUT, TEX_STRING(struct tex_common, format, 0, NULL, "EXT",
                                "format of standard output, e.g. png (default: exr)")},
    /* size, seed, ids and tile: the rows of prim.h, as in scenes and scripts */
    {TEX_OPT_SIZE, TEX_STRING(struct tex_common, size, 's', "256", "N|WxH", TEX_SIZE_HELP)},
    {TEX_OPT_SEED, TEX_SEED_ROW(struct tex_common, seed, 'S', 1)},
    {TEX_OPT_IDS, TEX_IDS_ROW(struct tex_common, ids)},
    {TEX_OPT_PALETTE, TEX_STRING(struct tex_common, palette, 0, NULL, "NAME|FILE",
                                 "colour the map through a palette")},
    {TEX_OPT_TILE, TEX_TILE_ROW(struct tex_common, tile)},
    {TEX_OPT_MAPS, TEX_STRING(struct tex_common, nonfinite, 0, "refuse", "refuse|keep|V",
                              "NaN and infinite samples in input maps: refuse the map naming "
                              "the first, keep them, or replace them by the number V")},
    {0, TEX_INT(struct tex_common, threads, 'j', 0, 0, 1024, "N",
                "threads to use (0: one per core)")},
    {0, TEX_FLAG(struct tex_common, quiet, 'q', "print no progress or warnings")},
};
#undef C
#define NCOMMON (sizeof common_rows / sizeof *common_rows)

static void vmsg(const char *kind, const char *fmt, va_list ap)
{
    fprintf(stderr, "%s: %s", tex_progname, kind);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

static void print_warning(const char *msg)
{
    fprintf(stderr, "%s: warning: %s\n", tex_progname, msg);
}

void tex_die(void)
{
    fprintf(stderr, "%s: error: %s\n", tex_progname, tex_errmsg());
    exit(tex_errkind() == TEX_ERR_USAGE ? 2 : 1);
}

void tex_usage_die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vmsg("error: ", fmt, ap);
    va_end(ap);
    exit(2);
}

/* At exit: text written to standard output (help, reports, palettes) must
 * have reached it; a full disk or a closed pipe is an error (exit 1). */
static void close_stdout(void)
{
    int bad = fflush(stdout) != 0 || ferror(stdout);
    int e = errno;

    if (fclose(stdout) != 0 && !bad) {
        e = errno;
        bad = e != EBADF; /* standard output closed and never written to */
    }
    if (bad) {
        fprintf(stderr, "%s: error: standard output: %s\n", tex_progname,
                e ? strerror(e) : "write error");
        fflush(stderr);
        _exit(1);
    }
}

/* One (row, struct) pair per option the tool accepts. */
struct opt {
    const struct tex_param *row;
    void *obj;
};

static int collect(const struct tex_tool *t, struct tex_common *c, void *opts, struct opt *o)
{
    int n = 0;

    for (size_t i = 0; i < NCOMMON; i++)
        if (!common_rows[i].mask || (t->common & common_rows[i].mask))
            o[n++] = (struct opt){&common_rows[i].row, c};
    for (const struct tex_param *p = t->params; p && p->name; p++)
        o[n++] = (struct opt){p, opts};
    return n;
}

static void usage_line(const struct tex_tool *t, FILE *fp)
{
    fprintf(fp, "usage: %s [options]%s%s\n", t->name, t->operands && *t->operands ? " " : "",
            t->operands ? t->operands : "");
}

static void print_help(const struct tex_tool *t, const struct opt *o, int n)
{
    usage_line(t, stdout);
    printf("%s.\n\nOptions:\n", t->summary);
    for (int i = 0; i < n; i++) {
        const struct tex_param *p = o[i].row;
        char opt[64], lhs[128], rng[128], def[64];
        tex_param_option(p, opt, sizeof opt);
        snprintf(lhs, sizeof lhs, "%c%c%s%s %s", p->key ? '-' : ' ', p->key ? p->key : ' ',
                 p->key ? ", " : "  ", opt,
                 p->type == TEX_P_FLAG ? "" : p->type == TEX_P_ENUM ? "NAME" : p->meta ? p->meta : "X");
        printf("  %-28s %s", lhs, p->help);
        tex_param_range(p, rng, sizeof rng);
        if (p->type != TEX_P_FLAG && p->type != TEX_P_STRING)
            printf(" [%s]", rng);
        if (p->type != TEX_P_FLAG && (p->type != TEX_P_STRING || p->defstr))
            printf(" (default %s)", tex_param_default(p, def, sizeof def));
        putchar('\n');
    }
    printf("  -h, --help                   show this help\n"
           "  -V, --version                show the version\n");
}

/* The option list as mdoc, for the man page (checked by the tests). */
static void print_mdoc(const struct opt *o, int n)
{
    puts(".Bl -tag -width Ds");
    for (int i = 0; i < n; i++) {
        const struct tex_param *p = o[i].row;
        char opt[64], rng[128], def[64];
        tex_param_option(p, opt, sizeof opt);
        printf(".It ");
        if (p->key)
            printf("Fl %c , ", p->key);
        printf("Fl %s", opt + 1);
        if (p->type != TEX_P_FLAG)
            printf(" Ar %s", p->type == TEX_P_ENUM ? "name" : p->meta ? p->meta : "x");
        printf("\n%c%s", p->help[0] >= 'a' && p->help[0] <= 'z' ? p->help[0] - 32 : p->help[0],
               p->help + 1);
        if (p->type == TEX_P_ENUM)
            printf(": one of %s", tex_param_range(p, rng, sizeof rng));
        else if (p->type != TEX_P_FLAG && p->type != TEX_P_STRING)
            printf(", %s", tex_param_range(p, rng, sizeof rng));
        if (p->type != TEX_P_FLAG && (p->type != TEX_P_STRING || p->defstr))
            printf("; default %s", tex_param_default(p, def, sizeof def));
        puts(".");
    }
    puts(".El");
}

static char *join_cmdline(int argc, char **argv)
{
    size_t n = 1;
    char *s, *e;

    for (int i = 0; i < argc; i++)
        n += 3 + 2 * strlen(argv[i]);
    if (!(s = malloc(n)))
        return NULL;
    e = s;
    for (int i = 0; i < argc; i++) {
        const char *a = i == 0 ? tex_progname : argv[i];
        int quote = *a == '\0' || strpbrk(a, " \t\n'\"\\$*?;&|<>()") != NULL;
        if (i)
            *e++ = ' ';
        if (quote)
            *e++ = '\'';
        for (; *a; a++) {
            if (*a == '\n') { /* history keeps one line per command */
                *e++ = ' ';
                continue;
            }
            if (*a == '\'' && quote) {
                memcpy(e, "'\\''", 4);
                e += 4;
                continue;
            }
            *e++ = *a;
        }
        if (quote)
            *e++ = '\'';
    }
    *e = '\0';
    return s;
}

/* Does the option word w (e.g. "-f" or "--frequency") take a separate value? */
static int takes_value(const struct option *lo, int n, const char *shorts, const char *w)
{
    if (w[0] != '-' || w[1] == '\0')
        return 0;
    if (w[1] != '-') {
        const char *s = w[2] == '\0' ? strchr(shorts, w[1]) : NULL;
        return s && s[1] == ':';
    }
    if (strchr(w, '='))
        return 0;
    for (int i = 0; i < n; i++)
        if (strcmp(lo[i].name, w + 2) == 0)
            return lo[i].has_arg == required_argument;
    return 0;
}

/* Fill c and opts with their defaults: the common rows the tool takes, then its own. */
static void set_defaults(const struct tex_tool *t, struct tex_common *c, void *opts)
{
    for (size_t i = 0; i < NCOMMON; i++)
        if (!common_rows[i].mask || (t->common & common_rows[i].mask)) {
            struct tex_param one[2] = {common_rows[i].row, {0}};
            tex_params_defaults(one, c);
        }
    if (t->params && tex_params_defaults(t->params, opts) < 0)
        tex_die();
}

/* getopt's tables for the n options o: long option i returns 256 + i and is named from
 * names[i]; then --help, --version and --help-mdoc. */
static void getopt_tables(const struct opt *o, int n, struct option *lo, char *shorts,
                          char (*names)[48])
{
    char *sp = shorts;

    *sp++ = ':'; /* options may follow operands, as in GNU tools; "--" ends them */
    for (int i = 0; i < n; i++) {
        const struct tex_param *p = o[i].row;
        tex_param_option(p, names[i], sizeof names[i]);
        lo[i] = (struct option){names[i] + 2,
                                p->type == TEX_P_FLAG ? no_argument : required_argument, NULL,
                                256 + i};
        if (p->key) {
            *sp++ = (char)p->key;
            if (p->type != TEX_P_FLAG)
                *sp++ = ':';
        }
    }
    strcpy(sp, "hV");
    lo[n] = (struct option){"help", no_argument, NULL, 'h'};
    lo[n + 1] = (struct option){"version", no_argument, NULL, 'V'};
    lo[n + 2] = (struct option){"help-mdoc", no_argument, NULL, 1};
    lo[n + 3] = (struct option){0};
}

/* Options may follow operands (GNU getopt permutes argv), but a negative
 * number such as "t_op add a.exr -0.5" is an operand: hide it from getopt
 * behind a marker byte, restored once parsing is done. */
static void hide_negatives(int argc, char **argv, const struct option *lo, int n,
                           const char *shorts)
{
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; i++) {
        double num;
        if (argv[i][0] == '-' && (isdigit((unsigned char)argv[i][1]) || argv[i][1] == '.') &&
            tex_parse_real(argv[i], &num) == 0 &&
            !(i > 1 && takes_value(lo, n, shorts, argv[i - 1]))) {
            char *h = malloc(strlen(argv[i]) + 2);
            if (!h) {
                tex_error("out of memory");
                tex_die();
            }
            h[0] = '\001';
            strcpy(h + 1, argv[i]);
            argv[i] = h;
        }
    }
}

/* One option k from getopt_long: help, version and the mdoc list print and exit, an
 * unknown option or a missing or bad value is a usage error. */
static void take_option(const struct tex_tool *t, int k, char **argv, const struct opt *o, int n)
{
    int i = -1;

    if (k == 'h') {
        print_help(t, o, n);
        exit(0);
    } else if (k == 'V') {
        printf("%s (Textura) %s\n", t->name, TEX_VERSION);
        exit(0);
    } else if (k == 1) {
        print_mdoc(o, n);
        exit(0);
    } else if (k == '?' || k == ':') {
        const char *bad = argv[optind - 1];
        if (optopt && optopt < 256)
            tex_usage_die("%s -%c (see %s --help)",
                          k == ':' ? "missing value for" : "unknown option", optopt, t->name);
        tex_usage_die("%s %s (see %s --help)", k == ':' ? "missing value for" : "unknown option",
                      bad, t->name);
    } else if (k >= 256) {
        i = k - 256;
    } else {
        for (int j = 0; j < n; j++)
            if (o[j].row->key == k)
                i = j;
    }
    if (i < 0 || tex_param_set(o[i].row, o[i].obj, optarg ? optarg : "") < 0)
        tex_die();
}

/* Once the options are read: -s's size, and as many operands as the tool takes. */
static void check_operands(const struct tex_tool *t, int argc, char **argv,
                           struct tex_common *c)
{
    int nops;

    if ((t->common & TEX_OPT_SIZE) && tex_parse_size(c->size, &c->w, &c->h) < 0)
        tex_usage_die("-s must be N or WxH with each side 1..%d (got '%s')", TEX_MAP_MAX_SIDE,
                      c->size);
    nops = argc - optind;
    if (nops < t->min_operands || (t->max_operands >= 0 && nops > t->max_operands)) {
        if (nops > t->min_operands)
            tex_usage_die("unexpected operand '%s' (usage: %s [options] %s)",
                          argv[optind + t->max_operands], t->name, t->operands);
        tex_usage_die("missing operand (usage: %s [options] %s)", t->name, t->operands);
    }
}

int tex_cli_parse(const struct tex_tool *t, int argc, char **argv, struct tex_common *c,
                  void *opts)
{
    struct opt o[128];
    struct option lo[132];
    char shorts[260], names[128][48];
    int n, k;

    tex_progname = t->name;
    memset(c, 0, sizeof *c);
    {
        static int registered; /* a tool may parse twice (t_warp) */
        if (!registered++)
            atexit(close_stdout);
    }
    n = collect(t, c, opts, o);
    set_defaults(t, c, opts);
    getopt_tables(o, n, lo, shorts, names);

    /* The history records the command line as typed, before getopt permutes it. */
    if (!(c->cmdline = join_cmdline(argc, argv))) {
        tex_error("out of memory");
        tex_die();
    }
    hide_negatives(argc, argv, lo, n, shorts);
    opterr = 0;
    optind = 1;
    while ((k = getopt_long(argc, argv, shorts, lo, NULL)) != -1)
        take_option(t, k, argv, o, n);
    for (int i = 1; i < argc; i++)
        if (argv[i][0] == '\001')
            argv[i]++; /* the marked copy is kept for the life of the program */
    check_operands(t, argc, argv, c);
    if (t->common & TEX_OPT_MAPS) {
        double v = 0;
        if (!strcmp(c->nonfinite, "refuse"))
            tex_map_set_nonfinite(TEX_NONFINITE_REFUSE, 0);
        else if (!strcmp(c->nonfinite, "keep"))
            tex_map_set_nonfinite(TEX_NONFINITE_KEEP, 0);
        else if (tex_parse_real(c->nonfinite, &v) == 0 && isfinite(v) && fabs(v) <= 3.4e38)
            tex_map_set_nonfinite(TEX_NONFINITE_REPLACE, (float)v);
        else
            tex_usage_die("--nonfinite must be refuse, keep or a finite number (got '%s')",
                          c->nonfinite);
    }
    tex_set_warning_handler(c->quiet ? NULL : print_warning);
#ifdef _OPENMP
    if (c->threads > 0)
        omp_set_num_threads(c->threads);
#endif
    return optind;
}

int tex_cli_depth(const struct tex_common *c)
{
    static const int bits[] = {0, 8, 16, 32}; /* the rows of --depth: auto|8|16|32 */
    return bits[c->depth_choice];
}

tex_map *tex_cli_read(const char *path)
{
    tex_map *m = tex_map_read(path);
    if (!m)
        tex_die();
    return m;
}

void tex_cli_write(tex_map *m, const struct tex_common *c)
{
    struct tex_write_opts o = {tex_cli_depth(c), (enum tex_compression)c->compression, c->format};

    if (c->cmdline && tex_map_add_history(m, c->cmdline) < 0)
        tex_die();
    if (tex_map_write(m, c->output, &o) < 0)
        tex_die();
}

/* The colours of subregions 1..n through the palette named. */
static float *region_colors(const char *palette, int n)
{
    tex_palette *pal = tex_palette_load(palette);
    float *c = pal ? tex_palette_region_colours(pal, n) : NULL;
    tex_palette_free(pal);
    return c;
}

void tex_cli_progress(long done, long total, void *arg)
{
    static const char bar[] = "########################################";
    int w = (int)sizeof bar - 1, k = total > 0 ? (int)(w * done / total) : w;
    (void)arg;
    fprintf(stderr, "\r%s: [%.*s%*s] %3d%%", tex_progname, k, bar, w - k, "",
            total > 0 ? (int)(100 * done / total) : 100);
    if (done >= total)
        fputc('\n', stderr);
}

int tex_cli_progress_wanted(const struct tex_common *c)
{
    return !c->quiet && isatty(2);
}

int tex_generate_main(const struct tex_primitive *p, int argc, char **argv)
{
    char name[64];
    snprintf(name, sizeof name, "t_%s", p->name);
    return tex_generate_main_rows(p, name, "", NULL, NULL, argc, argv);
}

int tex_generate_main_rows(const struct tex_primitive *p, const char *name,
                           const char *operands, const struct tex_param *rows, void *opts,
                           int argc, char **argv)
{
    float *colors = NULL;
    struct tex_common c;
    struct tex_field *f;
    tex_map *m;
    int nops = operands[0] != 0;
    struct tex_tool t = {name, operands, p->summary, TEX_OPT_OUTPUT | TEX_OPT_SIZE | TEX_OPT_SEED,
                         rows ? rows : p->params, nops, nops};

    if (p->flags & TEX_PRIM_TILE)
        t.common |= TEX_OPT_TILE;
    if (p->flags & TEX_PRIM_REGIONS)
        t.common |= TEX_OPT_IDS | TEX_OPT_PALETTE;
    if (!(f = tex_field_new(p)))
        tex_die();
    if (opts) /* the primitive's parameters lead the tool's own */
        memcpy(opts, f->params, p->params_size);
    tex_cli_parse(&t, argc, argv, &c, opts ? opts : f->params);
    if (opts)
        memcpy(f->params, opts, p->params_size);
    if (tex_map_write_check(c.output) < 0)
        tex_die(); /* now, not after the work */
    f->seed = (uint64_t)c.seed;
    f->tile = c.tile;
    f->ids = c.ids;
    if (c.palette && c.ids)
        tex_usage_die("--palette colours the subregions; --ids writes their ids instead: "
                      "give one of them");
    if (tex_field_init(f, c.w, c.h) < 0)
        tex_die();
    if (c.palette && !(colors = region_colors(c.palette, f->nregions)))
        tex_die();
    if (colors)
        f->colors = (const float(*)[3])colors;
    if (!(m = tex_field_sample(f)))
        tex_die();
    tex_cli_write(m, &c);
    tex_map_free(m);
    tex_field_free(f);
    free(colors);
    free(c.cmdline);
    return 0;
}
