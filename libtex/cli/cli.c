/* cli.c - options, help, errors and the generator main for every tool */
#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli/cli.h"
#include "base/error.h"
#include "base/progress.h"
#include "io/file.h"
#include "ops/palette.h"
#include "io/stream.h"

#ifndef TEX_VERSION
#define TEX_VERSION "0.1"
#endif

const char *tex_progname = "textura";

/* The common options: rows over struct tex_common, each with its mask bit. */
static const struct {
    unsigned mask;
    struct tex_param row;
} common_rows[] = {
    {TEX_OPT_OUTPUT, TEX_STRING(struct tex_common, output, 'o', NULL, "FILE",
                                "write to FILE, its format from the extension (default: the EXR "
                                "stream on standard output)")},
    {TEX_OPT_OUTPUT, TEX_ROW_ENUM("depth", struct tex_common, depth_choice, "auto", "auto|8|16|32",
                                  "bits per sample of integer formats, or 32 for float")},
    {TEX_OPT_OUTPUT,
     TEX_ROW_ENUM("compression", struct tex_common, compression, "zip", "none|zip|piz",
                  "compression of EXR files on disk (the stream is never compressed)")},
    {TEX_OPT_OUTPUT, TEX_STRING(struct tex_common, format, 0, NULL, "EXT",
                                "format of standard output, e.g. png (default: exr)")},
    {TEX_OPT_OUTPUT, TEX_FLAG(struct tex_common, exr_tiles, 0,
                              "write the EXR in 64 x 64 tiles instead of scanlines")},
    {TEX_OPT_OUTPUT, TEX_FLAG(struct tex_common, mipmap, 0,
                              "write a tiled EXR with its mip-map levels, as renderers' "
                              "texture files (.tx) have them")},
    /* size, seed, ids and tile: the rows of prim.h, as in scenes and scripts */
    {TEX_OPT_SIZE, TEX_STRING(struct tex_common, size, 's', "256", "N|WxH", TEX_SIZE_HELP)},
    {TEX_OPT_SEED, TEX_SEED_ROW(struct tex_common, seed, 'S', 1)},
    {TEX_OPT_IDS, TEX_IDS_ROW(struct tex_common, ids)},
    {TEX_OPT_PALETTE, TEX_STRING(struct tex_common, palette, 0, NULL, "NAME|FILE",
                                 "colour the map through a palette")},
    {TEX_OPT_TILE, TEX_TILE_ROW(struct tex_common, tile)},
    {TEX_OPT_WINDOW, TEX_STRING(struct tex_common, window, 0, NULL, "X,Y,W,H",
                                "make only the W x H window at X,Y of the -s map, the same "
                                "pixels as cropping the whole map")},
    {TEX_OPT_MAPS, TEX_STRING(struct tex_common, nonfinite, 0, "refuse", "refuse|keep|V",
                              "NaN and infinite samples in input maps: refuse the map naming "
                              "the first, keep them, or replace them by the number V")},
    {0, TEX_INT(struct tex_common, threads, 'j', 0, 0, 1024, "N",
                "threads to use (0: one per core)")},
    {0, TEX_FLAG(struct tex_common, quiet, 'q', "print no progress or warnings")},
};
#define NCOMMON (sizeof common_rows / sizeof *common_rows)

static int bar_drawn; /* a progress bar is on the last line of standard error */

/* Messages start on a line of their own. */
static void end_bar(void)
{
    if (bar_drawn)
        fputc('\n', stderr);
    bar_drawn = 0;
}

static void vmsg(const char *kind, const char *fmt, va_list ap)
{
    end_bar();
    fprintf(stderr, "%s: %s", tex_progname, kind);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

static void print_warning(const char *msg)
{
    end_bar();
    fprintf(stderr, "%s: warning: %s\n", tex_progname, msg);
}

void tex_die(void)
{
    tex_set_progress_handler(NULL, NULL); /* the bar ends where the work failed */
    end_bar();
    fprintf(stderr, "%s: error: %s\n", tex_progname, tex_errmsg());
    exit(tex_errkind() == TEX_ERR_USAGE ? 2 : 1);
}

void tex_usage_die(const char *fmt, ...)
{
    va_list ap;
    tex_set_progress_handler(NULL, NULL);
    va_start(ap, fmt);
    vmsg("error: ", fmt, ap);
    va_end(ap);
    exit(2);
}

/* At exit: text written to standard output (help, reports, palettes) must
 * have reached it; a full disk or a closed pipe is an error (exit 1). */
static void close_stdout(void)
{
    tex_progress_done();
    end_bar();
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
        snprintf(lhs, sizeof lhs, "%c%c%s%s%s%s %s", p->key ? '-' : ' ', p->key ? p->key : ' ',
                 p->key ? ", " : "  ", opt, p->alias ? ", --" : "", p->alias ? p->alias : "",
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
        if (p->alias)
            printf(" , Fl -%s", p->alias);
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

/* Options that cannot change the pixels: -j N, --threads N, -q, --quiet (and their
 * joined forms).  Returns how many words argv[i] and its value take, 0 if it is
 * not one. */
static int unrecorded(int argc, char **argv, int i)
{
    const char *a = argv[i];

    if (!strcmp(a, "-q") || !strcmp(a, "--quiet") || !strncmp(a, "--threads=", 10) ||
        (!strncmp(a, "-j", 2) && a[2]))
        return 1;
    if (!strcmp(a, "-j") || !strcmp(a, "--threads"))
        return i + 1 < argc ? 2 : 1;
    return 0;
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
    for (int i = 0, skip, ended = 0; i < argc; i++) {
        const char *a = i == 0 ? tex_progname : argv[i];
        if (i > 0 && !ended && (skip = unrecorded(argc, argv, i))) {
            i += skip - 1;
            continue;
        }
        ended |= i > 0 && !strcmp(a, "--");
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

/* Every long name getopt takes: the row's own, its US spelling, its
 * aliases and its deprecated old names; long option i returns 256 + i. */
#define MAXOPTS 160
#define MAXNAMES (4 * MAXOPTS)
struct lname {
    int opt;       /* index into the options o */
    int old;       /* deprecated: warn when used */
    char text[48]; /* without the dashes */
};
struct tables {
    struct option lo[MAXNAMES + 5]; /* and --help, --version, --help-mdoc, --help-options, 0 */
    struct lname names[MAXNAMES];
    int nnames;
    struct lname clashes[16]; /* a current name taken already by another row */
    int nclashes;
    char shorts[2 * 128 + 4];
    int short_opt[128], short_old[128]; /* option index of a short letter, -1 if none */
};

static void add_name(struct tables *tb, const struct opt *o, int i, const char *text, int old)
{
    const struct tex_param *p = o[i].row;
    struct lname *ln;

    for (int j = 0; j < tb->nnames; j++)
        if (!strcmp(tb->names[j].text, text)) {
            /* the first row of a name wins, as getopt would take it; an old name
             * may give way, a current one is a clash (--help-options shows it) */
            if (!old && tb->names[j].opt != i && tb->nclashes < 16) {
                tb->clashes[tb->nclashes] = (struct lname){i, 0, ""};
                snprintf(tb->clashes[tb->nclashes++].text, sizeof tb->names[0].text, "%s", text);
            }
            return;
        }
    if (tb->nnames == MAXNAMES)
        return;
    ln = &tb->names[tb->nnames];
    *ln = (struct lname){i, old, ""};
    snprintf(ln->text, sizeof ln->text, "%s", text);
    tb->lo[tb->nnames] = (struct option){ln->text,
                                         p->type == TEX_P_FLAG ? no_argument : required_argument,
                                         NULL, 256 + tb->nnames};
    tb->nnames++;
}

static void add_short(struct tables *tb, const struct opt *o, int i, int key, int old)
{
    char *sp = tb->shorts + strlen(tb->shorts);

    if (key <= 0 || key >= 128)
        return;
    if (tb->short_opt[key] >= 0) {
        if (!old && tb->short_opt[key] != i && tb->nclashes < 16) {
            tb->clashes[tb->nclashes] = (struct lname){i, 0, ""};
            snprintf(tb->clashes[tb->nclashes++].text, sizeof tb->names[0].text, "-%c", key);
        }
        return;
    }
    tb->short_opt[key] = i;
    tb->short_old[key] = old;
    *sp++ = (char)key;
    if (o[i].row->type != TEX_P_FLAG)
        *sp++ = ':';
    *sp = '\0';
}

/* Each word of a space-separated list: "-d" a short letter, else a long name. */
static void add_list(struct tables *tb, const struct opt *o, int i, const char *list, int old)
{
    char word[48];

    while (tex_param_list_next(&list, word, sizeof word))
        if (word[0] == '-' && word[1] && !word[2])
            add_short(tb, o, i, word[1], old);
        else
            add_name(tb, o, i, word, old);
}

/* getopt's tables for the n options o, then --help, --version, --help-mdoc and
 * --help-options.  Only the entries made are written: zeroing all 58 KB took a tool
 * 14 page faults (0.4 ms on a virtual machine). */
static void getopt_tables(const struct opt *o, int n, struct tables *tb)
{
    char name[64], us[64];

    tb->nnames = tb->nclashes = 0;
    memset(tb->short_opt, -1, sizeof tb->short_opt);
    memset(tb->short_old, 0, sizeof tb->short_old);
    strcpy(tb->shorts, ":hV"); /* options may follow operands, as in GNU tools; "--" ends them */
    for (int i = 0; i < n; i++) {
        tex_param_option(o[i].row, name, sizeof name);
        add_name(tb, o, i, name + 2, 0);
        add_short(tb, o, i, o[i].row->key, 0);
    }
    for (int i = 0; i < n; i++) { /* other names after every row's own */
        tex_param_option(o[i].row, name, sizeof name);
        add_name(tb, o, i, tex_param_us_spelling(name + 2, us, sizeof us), 0);
        add_list(tb, o, i, o[i].row->alias, 0);
    }
    for (int i = 0; i < n; i++)
        add_list(tb, o, i, o[i].row->old, 1);
    tb->lo[tb->nnames] = (struct option){"help", no_argument, NULL, 'h'};
    tb->lo[tb->nnames + 1] = (struct option){"version", no_argument, NULL, 'V'};
    tb->lo[tb->nnames + 2] = (struct option){"help-mdoc", no_argument, NULL, 1};
    tb->lo[tb->nnames + 3] = (struct option){"help-options", no_argument, NULL, 2};
    tb->lo[tb->nnames + 4] = (struct option){0};
}

/* Every name the tool takes, one a line: NAME, the row's option, how the name
 * stands to it (name, short, alias, spelling, old; clash for a name that
 * another row took first), type, argument: for the test that each flag
 * means one thing across the tools. */
static void print_names(const struct opt *o, const struct tables *tb)
{
    static const char *const types[] = {"int", "real", "flag", "enum", "reals",
                                        "colour", "string", "float", "special"};
    char name[64], rng[128], flag[64];

    /* the long names, then the short letters */
    for (int j = 0; j < tb->nnames + 128; j++) {
        int key = j - tb->nnames, i = key < 0 ? tb->names[j].opt : tb->short_opt[key];
        const char *how;
        if (i < 0)
            continue;
        const struct tex_param *p = o[i].row;
        tex_param_option(p, name, sizeof name);
        if (key >= 0) {
            how = tb->short_old[key] ? "old" : "short";
            snprintf(flag, sizeof flag, "-%c", key);
        } else {
            how = tb->names[j].old                        ? "old"
                : !strcmp(tb->names[j].text, name + 2)   ? "name"
                : tex_param_same_name(tb->names[j].text, name + 2) ? "spelling"
                                                                   : "alias";
            snprintf(flag, sizeof flag, "--%s", tb->names[j].text);
        }
        printf("%s\t%s\t%s\t%s\t%s\t%s\n", flag, name, how, types[p->type],
               p->meta ? p->meta : "-", tex_param_range(p, rng, sizeof rng));
    }
    for (int j = 0; j < tb->nclashes; j++)
        printf("%s%s\t%s\tclash\t-\t-\t-\n", tb->clashes[j].text[0] == '-' ? "" : "--",
               tb->clashes[j].text, tex_param_option(o[tb->clashes[j].opt].row, name, sizeof name));
}

/* Does the option word w (e.g. "-f" or "--frequency") take a separate value? */
static int takes_value(const struct tables *tb, const char *w)
{
    const struct option *lo = tb->lo;
    const char *shorts = tb->shorts;
    int n = tb->nnames;

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

/* Options may follow operands (GNU getopt permutes argv), but a negative
 * number such as "t_op add a.exr -0.5" is an operand: hide it from getopt
 * behind a marker byte, restored once parsing is done. */
static void hide_negatives(int argc, char **argv, const struct tables *tb)
{
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; i++) {
        double num;
        if (argv[i][0] == '-' && (isdigit((unsigned char)argv[i][1]) || argv[i][1] == '.') &&
            tex_parse_real(argv[i], &num) == 0 &&
            !(i > 1 && takes_value(tb, argv[i - 1]))) {
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

/* The rows given on the command line, and the deprecated names used. */
static struct {
    const struct tex_param *row;
    char as[48]; /* the name as typed: "-d", "--c" */
} given[MAXOPTS];
static int ngiven;
static struct {
    char name[48]; /* as typed: "-d", "--width" */
    int opt;
} old_used[8];
static int nold;

int tex_cli_given(const char *name)
{
    for (int i = 0; i < ngiven; i++)
        if (tex_param_same_name(given[i].row->name, name))
            return i + 1;
    return 0;
}

/* One option k from getopt_long: help, version and the lists print and exit, an
 * unknown option or a missing or bad value is a usage error. */
static void take_option(const struct tex_tool *t, int k, char **argv, const struct opt *o, int n,
                        const struct tables *tb)
{
    int i = -1, old = 0;

    if (k == 'h') {
        print_help(t, o, n);
        exit(0);
    } else if (k == 'V') {
        printf("%s (Textura) %s\n", t->name, TEX_VERSION);
        exit(0);
    } else if (k == 1) {
        print_mdoc(o, n);
        exit(0);
    } else if (k == 2) {
        print_names(o, tb);
        exit(0);
    } else if (k == '?' || k == ':') {
        const char *bad = argv[optind - 1];
        if (optopt && optopt < 256)
            tex_usage_die("%s -%c (see %s --help)",
                          k == ':' ? "missing value for" : "unknown option", optopt, t->name);
        tex_usage_die("%s %s (see %s --help)", k == ':' ? "missing value for" : "unknown option",
                      bad, t->name);
    } else if (k >= 256) {
        /* the word as typed: before its value when that came as the next word */
        const char *w = argv[optind - (optarg && optarg == argv[optind - 1] ? 2 : 1)];
        size_t len = strcspn(w + 2, "=");
        if (strncmp(w + 2, tb->names[k - 256].text, len) || tb->names[k - 256].text[len])
            tex_usage_die("unknown option %.*s: options are written whole (--%s?)",
                          (int)len + 2, w, tb->names[k - 256].text);
        i = tb->names[k - 256].opt;
        old = tb->names[k - 256].old;
    } else if (k > 0 && k < 128) {
        i = tb->short_opt[k];
        old = tb->short_old[k];
    }
    if (i < 0 || tex_param_set(o[i].row, o[i].obj, optarg ? optarg : "") < 0)
        tex_die();
    if (ngiven < MAXOPTS) {
        given[ngiven].row = o[i].row;
        if (k >= 256)
            snprintf(given[ngiven].as, sizeof given[ngiven].as, "--%s", tb->names[k - 256].text);
        else
            snprintf(given[ngiven].as, sizeof given[ngiven].as, "-%c", k);
        if (old && nold < 8) { /* warned once -q is known */
            snprintf(old_used[nold].name, sizeof old_used[nold].name, "%s", given[ngiven].as);
            old_used[nold++].opt = i;
        }
        ngiven++;
    }
}

/* The options of a mode (rows with kinds) when another mode was chosen. */
void tex_cli_check_kinds(const struct tex_tool *t, const char *choices, int kind,
                         const char *what)
{
    for (const struct tex_param *p = t->params; p && p->name; p++) {
        char list[256] = "";
        const char *c = choices;
        int g = tex_cli_given(p->name);
        if (!p->kinds || (p->kinds >> kind & 1) || !g)
            continue;
        for (int k = 0; *c; k++) {
            size_t len = strcspn(c, "|");
            if (p->kinds >> k & 1)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%.*s",
                         *list ? ", " : "", (int)len, c);
            c += len + (c[len] == '|');
        }
        tex_usage_die("%s applies to %s %s only", given[g - 1].as, what, list);
    }
}

/* Once the options are read: -s's size, and as many operands as the tool takes. */
static void check_operands(const struct tex_tool *t, int argc, char **argv,
                           struct tex_common *c)
{
    int nops;

    if ((t->common & TEX_OPT_SIZE) && tex_parse_size(c->size, &c->w, &c->h) < 0)
        tex_usage_die("-s must be N or WxH with each side 1..%d (got '%s')", TEX_MAP_MAX_SIDE,
                      c->size);
    if ((t->common & TEX_OPT_WINDOW) && c->window &&
        tex_parse_window(c->window, c->w, c->h, c->win) < 0)
        tex_usage_die("--window must be X,Y,W,H with W, H >= 1 inside the %dx%d map (got '%s')",
                      c->w, c->h, c->window);
    if ((t->common & TEX_OPT_OUTPUT) && (c->exr_tiles || c->mipmap)) {
        const char *out = c->output && strcmp(c->output, "-") ? c->output : NULL;
        char probe[40];
        snprintf(probe, sizeof probe, "x.%.32s", c->format ? c->format : "exr");
        if (tex_format_from_name(out ? out : probe) != TEX_FMT_EXR)
            tex_usage_die("%s writes EXR only (got %s)", c->mipmap ? "--mipmap" : "--exr-tiles",
                          out ? out : "--format");
    }
    nops = argc - optind;
    if (nops < t->min_operands || (t->max_operands >= 0 && nops > t->max_operands)) {
        if (nops > t->min_operands)
            tex_usage_die("unexpected operand '%s' (usage: %s [options] %s)",
                          argv[optind + t->max_operands], t->name, t->operands);
        tex_usage_die("missing operand (usage: %s [options] %s)", t->name, t->operands);
    }
}

/* Options that only apply together with others. */
static void check_combinations(const struct tex_tool *t, const struct tex_common *c,
                               const void *opts)
{
    const struct tex_param *mode = t->params ? tex_param_find(t->params, "mode") : NULL;

    if (c->output && c->format)
        tex_usage_die("--format applies to standard output only: -o %s takes its format from "
                      "the extension", c->output);
    if (mode && mode->type == TEX_P_ENUM)
        tex_cli_check_kinds(t, mode->choices, *(const int *)((const char *)opts + mode->off),
                            "--mode");
}

/* OpenMP's idle threads spin after every parallel region (libgomp polls 300000 times,
 * libomp for 200 ms) unless OMP_WAIT_POLICY is passive, and in a pipeline of tools on
 * busy cores that spinning takes the CPU the other stages need: a five-stage pipeline
 * spends about twice the CPU (tests/bench/omp_wait).  With libgomp, every tool's own getenv
 * answers the policy (omp_env.c).  LLVM's libomp reads the environment itself, as it loads,
 * before any code of a tool runs (a constructor, even one in .preinit_array, comes too late
 * or sees its setenv undone): built with clang, a tool whose environment names no policy
 * runs itself again, once, with OMP_WAIT_POLICY=passive; one set (to anything, e.g.
 * active) is kept.  Only at the start of a tool's main: nothing is open or printed yet.
 * A tool asked for one thread (its last -j or --threads is 1) starts none that could spin
 * and is not run again: the second start costs 1.5 ms. */
#if defined(_OPENMP) && defined(__clang__)
static int one_thread(char **argv)
{
    const char *last = NULL;
    for (int i = 1; argv[i] && strcmp(argv[i], "--") != 0; i++) {
        const char *a = argv[i];
        if (strncmp(a, "--threads=", 10) == 0)
            last = a + 10;
        else if (strncmp(a, "-j", 2) == 0 && a[2])
            last = a + 2;
        else if ((strcmp(a, "-j") == 0 || strcmp(a, "--threads") == 0) && argv[i + 1])
            last = argv[++i];
    }
    return last && strcmp(last, "1") == 0;
}
#endif

static void passive_threads(char **argv)
{
#if defined(_OPENMP) && defined(__clang__)
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT") || getenv("KMP_BLOCKTIME") ||
        one_thread(argv) || setenv("OMP_WAIT_POLICY", "passive", 1) < 0)
        return;
    execv("/proc/self/exe", argv); /* returns only on failure (no /proc): spin, then */
#else
    (void)argv;
#endif
}

int tex_cli_parse(const struct tex_tool *t, int argc, char **argv, struct tex_common *c,
                  void *opts)
{
    static struct tables tb; /* large: not on the stack */
    struct opt o[MAXOPTS];
    int n, k;

    tex_progname = t->name;
    memset(c, 0, sizeof *c);
    {
        static int registered; /* a tool may parse twice (t_warp) */
        if (!registered++) {
            passive_threads(argv);
            tex_keep_heap();
            atexit(close_stdout);
        }
    }
    ngiven = nold = 0;
    n = collect(t, c, opts, o);
    set_defaults(t, c, opts);
    getopt_tables(o, n, &tb);

    /* The history records the command line as typed, before getopt permutes it. */
    if (!(c->cmdline = join_cmdline(argc, argv))) {
        tex_error("out of memory");
        tex_die();
    }
    hide_negatives(argc, argv, &tb);
    opterr = 0;
    optind = 1;
    while ((k = getopt_long(argc, argv, tb.shorts, tb.lo, NULL)) != -1)
        take_option(t, k, argv, o, n, &tb);
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
    check_combinations(t, c, opts);
    tex_set_warning_handler(c->quiet ? NULL : print_warning);
    tex_set_progress_handler(tex_cli_progress_wanted(c) ? tex_cli_progress : NULL, NULL);
    for (int i = 0; i < nold; i++) {
        char name[64];
        tex_param_option(o[old_used[i].opt].row, name, sizeof name);
        if (tex_param_deprecated_is_error())
            tex_usage_die("%s is deprecated: write %s (TEXTURA_DEPRECATED=error)",
                          old_used[i].name, name);
        tex_warning("%s is deprecated and will be removed: write %s", old_used[i].name, name);
    }
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
    struct tex_write_opts o = {tex_cli_depth(c), (enum tex_compression)c->compression, c->format,
                               c->exr_tiles, c->mipmap};

    tex_progress_done();
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

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

void tex_cli_progress(long done, long total, void *arg)
{
    static const char bar[] = "########################################";
    static double start = -1;
    int w = (int)sizeof bar - 1, k = total > 0 ? (int)(w * done / total) : w;
    (void)arg;
    if (start < 0)
        start = seconds();
    if (!bar_drawn && seconds() - start < 0.3)
        return; /* work that ends within a moment draws no bar */
    bar_drawn = done < total;
    fprintf(stderr, "\r%s: [%.*s%*s] %3d%%", tex_progname, k, bar, w - k, "",
            total > 0 ? (int)(100 * done / total) : 100);
    if (done >= total)
        fputc('\n', stderr);
}

int tex_cli_progress_wanted(const struct tex_common *c)
{
    return !c->quiet && isatty(2);
}

struct gen_job {
    struct tex_field *f;
    int x, y, w; /* the window the bands cut (the whole grid without --window) */
};

/* A band sampled straight into the encoder's rows: a map of its own for each band
 * would be fresh memory each time, and a first touch of a page is dear. */
static int gen_fill(void *arg, int y, int n, float *rows)
{
    struct gen_job *j = arg;
    tex_map b = {.w = j->w, .h = n, .nc = tex_field_channels(j->f), .px = rows};
    int rc;

    j->f->wx = j->x;
    j->f->wy = j->y + y;
    j->f->ww = j->w;
    j->f->wh = n;
    memset(rows, 0, tex_map_samples(&b) * sizeof *rows); /* as tex_map_new's maps come */
    tex_progress_hold(1); /* the band counts as its rows of the whole map */
    rc = tex_field_sample_into(j->f, &b);
    tex_progress_hold(0);
    if (rc < 0)
        return -1;
    tex_progress_add(n);
    return 0;
}

void tex_cli_write_rows(tex_map *head, const struct tex_common *c, tex_rows_fn fill, void *arg)
{
    struct tex_out o = {.fd = 1};
    const char *oname = "standard output";
    int rc;

    if (c->cmdline && tex_map_add_history(head, c->cmdline) < 0)
        tex_die();
    if (c->output && strcmp(c->output, "-")) {
        if (tex_out_open(&o, c->output) < 0) {
            tex_out_close(&o, -1);
            tex_die();
        }
        oname = c->output;
    }
    rc = tex_exr_write_rows(head, fill, arg, 0, (enum tex_compression)c->compression, o.fd,
                            oname);
    if (o.fd != 1)
        rc = tex_out_close(&o, rc);
    if (rc < 0)
        tex_die();
}

static int gen_probe(struct gen_job *j, tex_map **probe)
{
    struct tex_field *f = j->f;
    int saved[4] = {f->wx, f->wy, f->ww, f->wh};
    f->wx = j->x;
    f->wy = j->y;
    f->ww = f->wh = 1;
    *probe = tex_field_sample(f);
    f->wx = saved[0], f->wy = saved[1], f->ww = saved[2], f->wh = saved[3];
    return *probe ? 0 : -1;
}

/* A generator's map written as it is sampled, a band of rows at a time. */
static void generate_bands(struct tex_field *f, const struct tex_common *c)
{
    int win = f->ww > 0;
    struct gen_job j = {f, win ? f->wx : 0, win ? f->wy : 0, win ? f->ww : f->w};
    tex_map head = {0};
    tex_map *probe;
    head.w = j.w;
    head.h = win ? f->wh : f->h;
    /* channels and subregions as the sampler makes them: its first pixel */
    if (gen_probe(&j, &probe) < 0)
        tex_die();
    head.nc = probe->nc;
    head.subregions = probe->subregions;
    tex_map_free(probe);
    if (win) {
        head.x0 = f->wx;
        head.y0 = f->wy;
        head.full_w = f->w;
        head.full_h = f->h;
    }
    tex_progress_stage(1, head.h);
    tex_cli_write_rows(&head, c, gen_fill, &j);
    free(head.history);
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
    struct tex_tool t = {name, operands, p->summary,
                         TEX_OPT_OUTPUT | TEX_OPT_SIZE | TEX_OPT_SEED | TEX_OPT_WINDOW,
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
    if (c.win[2] > 0 && tex_field_window(f, c.win[0], c.win[1], c.win[2], c.win[3]) < 0)
        tex_die();
    if (tex_field_init(f, c.w, c.h) < 0)
        tex_die();
    if (c.palette && !(colors = region_colors(c.palette, f->nregions)))
        tex_die();
    if (colors)
        f->colors = (const float(*)[3])colors;
    if (tex_cli_streams(&c) && !tex_field_whole(f)) {
        generate_bands(f, &c); /* the same pixels, a band of rows at a time */
    } else {
        if (!(m = tex_field_sample(f)))
            tex_die();
        tex_cli_write(m, &c);
        tex_map_free(m);
    }
    tex_field_free(f);
    free(colors);
    free(c.cmdline);
    return 0;
}

/* ---- per-pixel tools in bands ---- */

struct band_job {
    tex_rows_reader *r;
    const char *name;
    int w, nc, subregions;
    tex_map *(*op)(tex_map *, void *);
    void *arg;
    tex_map *keep; /* a band the op gave back as it took it, for the next band's rows */
};

/* The op's band is the last one's map where the op gave that back (the bands are one
 * size but the last): a map of its own for each band would be fresh pages each time. */
static int band_fill(void *arg, int y, int n, float *rows)
{
    struct band_job *j = arg;
    tex_map *b = j->keep, *o;

    j->keep = NULL;
    if (b && b->h < n) {
        tex_map_free(b);
        b = NULL;
    }
    if (!b && !(b = tex_map_new(j->w, n, j->nc)))
        return -1;
    b->h = n;
    b->subregions = j->subregions;
    if (tex_rows_read(j->r, y, n, b->px, j->name) < 0 ||
        tex_rows_nonfinite(b->px, j->w, n, j->nc, y, j->name) < 0 || !(o = j->op(b, j->arg))) {
        tex_map_free(b);
        return -1;
    }
    memcpy(rows, o->px, tex_map_samples(o) * sizeof *rows);
    if (o->w == j->w && o->nc == j->nc)
        j->keep = o;
    else
        tex_map_free(o);
    return 0;
}

int tex_cli_streams(const struct tex_common *c)
{
    if (c->exr_tiles || c->mipmap || (c->format && strcmp(c->format, "exr") != 0))
        return 0;
    return !c->output || !strcmp(c->output, "-") ||
           tex_format_from_name(c->output) == TEX_FMT_EXR;
}

void tex_cli_stream(const char *path, const struct tex_common *c,
                    tex_map *(*op)(tex_map *band, void *arg), void *arg)
{
    const char *name = path && strcmp(path, "-") ? path : "standard input";
    tex_map head, *whole = NULL, *probe, *m;
    tex_rows_reader *r = NULL;

    if (tex_map_write_check(c->output) < 0)
        tex_die();
    if (tex_cli_streams(c)) {
        r = tex_map_open_rows(path, &head, &whole);
        if (!r && !whole)
            tex_die();
    } else {
        whole = tex_cli_read(path);
    }
    if (!r) { /* the same op over the whole map */
        if (!(m = op(whole, arg)))
            tex_die();
        tex_cli_write(m, c);
        tex_map_free(m);
        return;
    }
    if (!(probe = tex_map_new(1, 1, head.nc)))
        tex_die();
    for (int k = 0; k < head.nc; k++)
        probe->px[k] = 1;
    probe->subregions = head.subregions;
    if (!(probe = op(probe, arg)))
        tex_die();
    {
        struct band_job j = {r, name, head.w, head.nc, head.subregions, op, arg, NULL};
        tex_map out = head;
        out.nc = probe->nc;
        out.subregions = probe->subregions;
        tex_map_free(probe);
        tex_cli_write_rows(&out, c, band_fill, &j);
        tex_map_free(j.keep);
        tex_rows_close(r);
        free(out.history);
    }
}
