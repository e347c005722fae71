/* options.c - the tools' options from parameter rows: getopt's tables, taking each option,
 * the operands and the options that go together, and the command line for the history */
#include <ctype.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/internal.h"
#include "base/nearest.h"
#include "base/error.h"
#include "base/progress.h"
#include "io/file.h"

#ifndef TEX_VERSION
#define TEX_VERSION "0.1"
#endif

/* The common options: rows over struct tex_common, each with its mask bit. */
static const struct {
    unsigned mask;
    struct tex_param row;
} common_rows[] = {
    {TEX_OPT_OUTPUT, TEX_STRING(struct tex_common, output, 'o', NULL, "FILE",
                                "write to FILE, its format from a FMT: prefix (png:-), --format "
                                "or the extension; a stream without one gets EXR (default: "
                                "standard output)")},
    {TEX_OPT_OUTPUT, TEX_ROW_ENUM("depth", struct tex_common, depth_choice, "auto", "auto|8|16|32",
                                  "bits per sample of integer formats, or 32 for float")},
    {TEX_OPT_OUTPUT,
     TEX_ROW_ENUM("compression", struct tex_common, compression, "zip", "none|zip|piz",
                  "compression of EXR files on disk (the stream is never compressed)")},
    {TEX_OPT_OUTPUT, TEX_STRING(struct tex_common, format, 0, NULL, "EXT",
                                "the output's format, as an extension names it, e.g. png "
                                "(default: -o's extension, else exr)")},
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

static int collect(const struct tex_tool *t, struct tex_common *c, void *opts, struct tex_cli_opt *o)
{
    int n = 0;

    for (size_t i = 0; i < NCOMMON; i++)
        if (!common_rows[i].mask || (t->common & common_rows[i].mask))
            o[n++] = (struct tex_cli_opt){&common_rows[i].row, c};
    for (const struct tex_param *p = t->params; p && p->name; p++)
        o[n++] = (struct tex_cli_opt){p, opts};
    return n;
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
    struct option lo[MAXNAMES + 8]; /* and --help, --version, --help-mdoc, --help-options,
                                      * --help-synopsis, --help-common-mdoc, --help-json, 0 */
    struct lname names[MAXNAMES];
    int nnames;
    struct lname clashes[16]; /* a current name taken already by another row */
    int nclashes;
    char shorts[2 * 128 + 4];
    int short_opt[128], short_old[128]; /* option index of a short letter, -1 if none */
};

static void add_name(struct tables *tb, const struct tex_cli_opt *o, int i, const char *text, int old)
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
                                         p->type == TEX_P_FLAG ? no_argument
                                         : p->bare             ? optional_argument
                                                               : required_argument,
                                         NULL, 256 + tb->nnames};
    tb->nnames++;
}

static void add_short(struct tables *tb, const struct tex_cli_opt *o, int i, int key, int old)
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
static void add_list(struct tables *tb, const struct tex_cli_opt *o, int i, const char *list, int old)
{
    char word[48];

    while (tex_param_list_next(&list, word, sizeof word))
        if (word[0] == '-' && word[1] && !word[2])
            add_short(tb, o, i, word[1], old);
        else
            add_name(tb, o, i, word, old);
}

/* getopt's tables for the n options o, then --help, --version, --help-mdoc and
 * --help-options.  Only the entries made are written: zeroing the whole tables would
 * touch pages a tool never needs (doc/performance.md). */
static void getopt_tables(const struct tex_cli_opt *o, int n, struct tables *tb)
{
    char name[64], us[64];

    tb->nnames = tb->nclashes = 0;
    memset(tb->short_opt, -1, sizeof tb->short_opt);
    memset(tb->short_old, 0, sizeof tb->short_old);
    /* '-': operands come back in order as 1, and read_options puts them last itself:
     * options may follow operands, as in GNU tools, even under POSIXLY_CORRECT (which
     * would make getopt stop at the first operand); "--" ends them.  ':': a missing
     * value is ':', not '?'. */
    strcpy(tb->shorts, "-:hV");
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
    tb->lo[tb->nnames + 2] = (struct option){"help-mdoc", no_argument, NULL, 3};
    tb->lo[tb->nnames + 3] = (struct option){"help-options", no_argument, NULL, 2};
    tb->lo[tb->nnames + 4] = (struct option){"help-synopsis", no_argument, NULL, 4};
    tb->lo[tb->nnames + 5] = (struct option){"help-common-mdoc", no_argument, NULL, 5};
    tb->lo[tb->nnames + 6] = (struct option){"help-json", no_argument, NULL, 6};
    tb->lo[tb->nnames + 7] = (struct option){0};
}

/* Every name the tool takes, one a line: NAME, the row's option, how the name
 * stands to it (name, short, alias, spelling, old; clash for a name that
 * another row took first), type, argument: for the test that each flag
 * means one thing across the tools. */
static void print_names(const struct tex_cli_opt *o, const struct tables *tb)
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

/* An unknown long option: the message names the nearest current one, if one is near. */
static void unknown_long(const struct tex_tool *t, const char *bad, const struct tables *tb)
{
    struct tex_nearest nr;
    char word[64];
    const char *near;

    snprintf(word, sizeof word, "%.*s", (int)strcspn(bad + 2, "="), bad + 2);
    tex_nearest_init(&nr, word);
    for (int i = 0; i < tb->nnames; i++)
        if (!tb->names[i].old)
            tex_nearest_try(&nr, tb->names[i].text, strlen(tb->names[i].text));
    for (int i = tb->nnames; tb->lo[i].name; i++) /* --help, --version... */
        tex_nearest_try(&nr, tb->lo[i].name, strlen(tb->lo[i].name));
    if ((near = tex_nearest_name(&nr)))
        tex_usage_die("unknown option %s; did you mean --%s? (see %s --help)", bad, near, t->name);
}

/* One option k from getopt_long: help, version and the lists print and exit, an
 * unknown option or a missing or bad value is a usage error. */
/* Whether word is one of choices ("a|b|c") */
static int is_choice(const char *choices, const char *word)
{
    size_t len = strlen(word);
    for (const char *c = choices; *c; c += strcspn(c, "|"), c += *c == '|')
        if (strcspn(c, "|") == len && !strncmp(c, word, len))
            return 1;
    return 0;
}

static void take_option(const struct tex_tool *t, int k, int argc, char **argv,
                        const struct tex_cli_opt *o, int n, const struct tables *tb)
{
    int i = -1, old = 0;

    if (k == 'h') {
        tex_cli_help(stdout, t, o, n);
        exit(0);
    } else if (k == 'V') {
        printf("%s (Textura) %s\n", t->name, TEX_VERSION);
        exit(0);
    } else if (k == 3) {
        tex_cli_mdoc(stdout, t, o, n);
        exit(0);
    } else if (k == 5) { /* every tool's shared options, for textura(5) */
        struct tex_cli_opt all[NCOMMON];
        for (size_t j = 0; j < NCOMMON; j++)
            all[j] = (struct tex_cli_opt){&common_rows[j].row, NULL};
        tex_cli_mdoc(stdout, NULL, all, (int)NCOMMON);
        exit(0);
    } else if (k == 4) {
        tex_cli_synopsis(stdout, t, o, n);
        exit(0);
    } else if (k == 6) {
        tex_cli_json(stdout, t);
        exit(0);
    } else if (k == 2) {
        print_names(o, tb);
        exit(0);
    } else if (k == '?' || k == ':') {
        const char *bad = argv[optind - 1];
        if (optopt && optopt < 256)
            tex_usage_die("%s -%c (see %s --help)",
                          k == ':' ? "missing value for" : "unknown option", optopt, t->name);
        if (k == '?' && !strncmp(bad, "--", 2))
            unknown_long(t, bad, tb);
        tex_usage_die("%s %s (see %s --help)", k == ':' ? "missing value for" : "unknown option",
                      bad, t->name);
    } else if (k >= 256) {
        const struct tex_param *row = o[tb->names[k - 256].opt].row;
        if (!optarg && row->bare && optind < argc && is_choice(row->choices, argv[optind]))
            optarg = argv[optind++]; /* "--preview sixel": the next word is a choice */
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
    if (i < 0 || tex_param_set(o[i].row, o[i].obj,
                               optarg ? optarg : o[i].row->bare ? o[i].row->bare : "") < 0)
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
        tex_usage_die("-s must be N or WxH with " TEX_MAP_SIZE_RULE " (got '%s')", c->size);
    if ((t->common & TEX_OPT_WINDOW) && c->window &&
        tex_parse_window(c->window, c->w, c->h, c->win) < 0)
        tex_usage_die("--window must be X,Y,W,H with W, H >= 1 inside the %dx%d map (got '%s')",
                      c->w, c->h, c->window);
    if ((t->common & TEX_OPT_OUTPUT) && (c->format || c->exr_tiles || c->mipmap)) {
        /* the output's format, before any work (-o alone may name a palette file) */
        const char *file;
        enum tex_format f = tex_output_format(c->output, c->format, &file);
        if (f == TEX_FMT_UNKNOWN)
            tex_die();
        if ((c->exr_tiles || c->mipmap) && f != TEX_FMT_EXR)
            tex_usage_die("%s writes EXR only (got %s)", c->mipmap ? "--mipmap" : "--exr-tiles",
                          c->format ? c->format : c->output);
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
static void check_combinations(const struct tex_tool *t, const void *opts)
{
    const struct tex_param *mode = t->params ? tex_param_find(t->params, "mode") : NULL;

    if (mode && mode->type == TEX_P_ENUM)
        tex_cli_check_kinds(t, mode->choices, *(const int *)((const char *)opts + mode->off),
                            "--mode");
}

/* argv[from..to) moved in front of argv[at..from), each part in its order. */
static void rotate(char **argv, int at, int from, int to)
{
    for (; from < to; from++, at++) {
        char *w = argv[from];
        memmove(argv + at + 1, argv + at, (size_t)(from - at) * sizeof *argv);
        argv[at] = w;
    }
}

/* Every option taken, in the order typed, with getopt in order ('-': an operand comes
 * back as 1) and the operands moved after the options as they come, in their order, as
 * GNU getopt's permutation leaves argv; optind at the first operand.  argv[1..first)
 * holds the options read, argv[first..first + nops) the operands. */
static void read_options(const struct tex_tool *t, int argc, char **argv,
                         const struct tex_cli_opt *o, int n, const struct tables *tb)
{
    int first = 1, nops = 0, k;

    opterr = 0;
    optind = 0; /* getopt starts afresh, as for another process */
    while ((k = getopt_long(argc, argv, tb->shorts, tb->lo, NULL)) != -1) {
        if (k == 1) { /* the word after the operands so far, getopt leaving it in place */
            nops++;
            continue;
        }
        take_option(t, k, argc, argv, o, n, tb);
        rotate(argv, first, first + nops, optind); /* the option's words, ahead */
        first = optind - nops;
    }
    if (optind > first + nops) { /* "--", ahead of the operands as GNU getopt puts it */
        rotate(argv, first, first + nops, optind);
        first = optind - nops;
    }
    optind = first;
}

int tex_cli_parse(const struct tex_tool *t, int argc, char **argv, struct tex_common *c,
                  void *opts)
{
    static struct tables tb; /* large: not on the stack */
    struct tex_cli_opt o[MAXOPTS];
    int n;

    tex_progname = t->name;
    memset(c, 0, sizeof *c);
    {
        static int registered; /* a process may parse more than once (the unit tests) */
        if (!registered++) {
            tex_cli_passive_threads(argv);
            tex_keep_heap();
            atexit(tex_cli_close_stdout);
        }
    }
    ngiven = nold = 0;
    n = collect(t, c, opts, o);
    set_defaults(t, c, opts);
    getopt_tables(o, n, &tb);

    /* The history records the command line as typed, before the operands move last. */
    if (!(c->cmdline = join_cmdline(argc, argv))) {
        tex_error("out of memory");
        tex_die();
    }
    hide_negatives(argc, argv, &tb);
    read_options(t, argc, argv, o, n, &tb);
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
    check_combinations(t, opts);
    tex_set_warning_handler(c->quiet ? NULL : tex_cli_warning);
    tex_set_progress_handler(tex_cli_progress_wanted(c) ? tex_cli_progress : NULL, NULL);
    for (int i = 0; i < nold; i++) {
        char name[64];
        tex_param_option(o[old_used[i].opt].row, name, sizeof name);
        if (tex_param_deprecated_is_error())
            tex_usage_die("%s is deprecated: write %s (TEXTURA_DEPRECATED=error)",
                          old_used[i].name, name);
        tex_warning("%s is deprecated and will be removed: write %s", old_used[i].name, name);
    }
    tex_cli_threads(c->threads);
    return optind;
}
