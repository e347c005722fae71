/* cli.h - the tools' shared command-line front end
 *
 * Every tool parses its options here, with getopt_long, from parameter
 * tables (param.h): the common options below, chosen by a mask, plus the
 * tool's own rows.  An option is taken by its row's name, in UK or US
 * spelling, by the row's aliases, and by its old names with a warning that
 * they are deprecated (textura(5) gives the naming rule).  Options a mode
 * does not use are refused (tex_cli_check_kinds), and so is --format with -o.
 * The front end prints --help and --version from the same rows, reports
 * errors as "t_noise: error: ..." on stderr and exits
 * with 2 for usage errors and 1 for runtime errors.  It is the one part of
 * libtex that prints and exits: it stands for the tool's main.
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
#ifndef TEX_CLI_H
#define TEX_CLI_H

#include <stdint.h>

#include "../base/map.h"
#include "../base/param.h"
#include "../prim/prim.h"

#ifdef __cplusplus
extern "C" {
#endif

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

extern const char *tex_progname;

/* Parse argv; returns the index of the first operand (getopt has moved the
 * options before the operands, which keep their order).  c->cmdline records
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
/* Print "prog: error: <tex_errmsg()>" and exit with its kind's status. */
void tex_die(void) __attribute__((noreturn));
/* Print "prog: error: ..." and exit 2 (usage). */
void tex_usage_die(const char *fmt, ...) __attribute__((noreturn, format(printf, 1, 2)));
/* Read a map or die. */
tex_map *tex_cli_read(const char *path);
/* The bit depth that --depth chose: 0 (auto), 8, 16 or 32. */
int tex_cli_depth(const struct tex_common *c);
/* Append the command line to the history and write the map to -o or
 * standard output, or die. */
void tex_cli_write(tex_map *m, const struct tex_common *c);

/* A map made a band of rows at a time, never held whole: where -o (or the
 * format) asks for a scanline EXR (tex_cli_streams), head (size, channels,
 * place; its history gains the command line) is written to -o or standard
 * output as fill makes its rows, as tex_exr_write_rows (io/stream.h) calls
 * it; dies on errors. */
int tex_cli_streams(const struct tex_common *c);
void tex_cli_write_rows(tex_map *head, const struct tex_common *c,
                        int (*fill)(void *arg, int y, int n, float *rows), void *arg);

/* A progress bar on standard error, "t_NAME: [####    ]  50%", ending the
 * line at done == total, drawn once the work has run 0.3 s: for libtex's
 * progress callbacks (pass it only when standard error is a terminal and -q
 * is off: tex_cli_progress_wanted).  tex_cli_parse makes it the process's
 * progress handler (progress.h) under the same conditions, and
 * tex_cli_write completes it. */
void tex_cli_progress(long done, long total, void *arg);
int tex_cli_progress_wanted(const struct tex_common *c);

/* A per-pixel tool's work in bounded memory: the map at path (NULL or "-":
 * standard input) goes through op a band of rows at a time, each band a
 * small map of the input's width (op changes it in place and returns it, or
 * returns a new map and frees the band; NULL with the error set on
 * failure), and out to -o or standard output, with the history.  Output
 * channels and subregions are op's on a 1 x 1 band of ones.  When input or
 * output is not a scanline EXR (another format, tiles, --mipmap), the map
 * goes through op whole instead: the same pixels either way, op being
 * per-pixel.  Dies on errors. */
void tex_cli_stream(const char *path, const struct tex_common *c,
                    tex_map *(*op)(tex_map *band, void *arg), void *arg);

/* The whole main of a generator tool t_NAME: parse, sample, write. */
int tex_generate_main(const struct tex_primitive *p, int argc, char **argv);
/* The same for a tool named name whose options are more than the
 * primitive's: rows over opts, a struct that begins with the primitive's
 * parameter struct (p->params_size bytes, the defaults copied in before
 * parsing); operands: the usage text of its one operand ("" for none). */
int tex_generate_main_rows(const struct tex_primitive *p, const char *name,
                           const char *operands, const struct tex_param *rows, void *opts,
                           int argc, char **argv);

#ifdef __cplusplus
}
#endif
#endif
