/* options.h - a tool's options, parsed from parameter rows
 *
 * Every tool parses its options here, with getopt_long, from parameter
 * tables (param.h): the common options below, chosen by a mask, plus the
 * tool's own rows.  An option is taken by its row's name, in UK or US
 * spelling, by the row's aliases, and by its old names with a warning that
 * they are deprecated (textura(5) gives the naming rule).  Options may follow
 * the operands, as in GNU tools, whatever POSIXLY_CORRECT says; "--" ends them.
 * Options a mode does not use are refused (tex_cli_check_kinds), and so is
 * --format with -o.  --help, --help-mdoc, --help-json and --version print from the same
 * rows.
 *
 *   static struct opts { int json; } o;
 *   static const struct tex_param rows[] = {TEX_FLAG(struct opts, json, 0, "..."), {0}};
 *   static const struct tex_tool tool = {"t_info", "[MAP]", "statistics of a map",
 *                                        0, rows, 0, 1};
 *   struct tex_common c;
 *   int i = tex_cli_parse(&tool, argc, argv, &c, &o);   // argv[i..] are the operands
 *
 * Common options (mask bits):
 *   TEX_OPT_OUTPUT   -o FILE, --depth auto|8|16|32, --compression none|zip|piz,
 *                    --format EXT (of standard output), --exr-tiles, --mipmap (EXR only)
 *   TEX_OPT_SIZE     -s N|WxH
 *   TEX_OPT_SEED     -S/--seed N
 *   TEX_OPT_IDS      --ids
 *   TEX_OPT_PALETTE  --palette NAME|FILE
 *   TEX_OPT_TILE     --tile
 *   TEX_OPT_WINDOW   --window X,Y,W,H (a window of the -s map; c->win, win[2] 0: none)
 *   TEX_OPT_MAPS     --nonfinite refuse|keep|V (input maps' NaN and infinities, file.h)
 *   always           -j/--threads N, -q/--quiet, -h/--help, -V/--version
 */
#ifndef TEX_CLI_OPTIONS_H
#define TEX_CLI_OPTIONS_H

#include "../base/api.h"
#include "../base/param.h"

TEX_API_BEGIN

enum {
    TEX_OPT_OUTPUT = 1 << 0,
    TEX_OPT_SIZE = 1 << 1,
    TEX_OPT_SEED = 1 << 2,
    TEX_OPT_IDS = 1 << 3,
    TEX_OPT_PALETTE = 1 << 4,
    TEX_OPT_TILE = 1 << 5,
    TEX_OPT_MAPS = 1 << 6,
    TEX_OPT_WINDOW = 1 << 7,
};

struct tex_common {
    const char *output; /* NULL: standard output */
    int depth_choice;   /* index into auto|8|16|32 */
    int compression;    /* enum tex_compression */
    const char *format;
    int exr_tiles, mipmap; /* EXR output in tiles, with mip-map levels */
    const char *size;
    int w, h;           /* parsed from size */
    int seed;
    int threads;        /* 0: OpenMP's default */
    int quiet;
    int ids;
    const char *palette;
    int tile;
    const char *nonfinite;
    const char *window;
    int win[4];         /* parsed from window: x, y, w, h; w 0 when none */
    char *cmdline;      /* the command line, for the map's history */
};

struct tex_tool {
    const char *name;     /* "t_info" */
    const char *operands; /* usage text after the options, e.g. "[MAP]" */
    const char *summary;  /* one line */
    unsigned common;      /* TEX_OPT_* */
    const struct tex_param *params; /* the tool's own options, or NULL */
    int min_operands, max_operands; /* max < 0: any number */
};

/* Parse argv; returns the index of the first operand (the options are moved
 * before the operands, which keep their order).  c->cmdline records
 * the command line as typed, less the options that cannot change the output
 * (-j, -q), so that the same map has the same bytes.  Exits on --help,
 * --version, --help-options (every name taken, for the tests) and errors. */
int tex_cli_parse(const struct tex_tool *t, int argc, char **argv, struct tex_common *c,
                  void *opts);
/* Was the option named (its row's name, in either spelling) on the command line?
 * Nonzero if it was. */
int tex_cli_given(const char *name);
/* Refuse each of the tool's options that was given and whose row's kinds
 * (bit k: mode k of choices "a|b|c") leave out mode kind: "--c applies to
 * --mode julia only".  what names the choice ("--mode", "the operation").
 * tex_cli_parse does this itself for a tool whose rows have an ENUM "mode". */
void tex_cli_check_kinds(const struct tex_tool *t, const char *choices, int kind,
                         const char *what);

TEX_API_END
#endif
