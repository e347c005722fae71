/* param.h - parameter tables: one row declares one parameter
 *
 * A row gives a parameter's name, type, default, range and one-line help,
 * and where its value lives (an offset into a struct).  From the same
 * rows come the defaults, the range checks, --help, the man page's
 * parameter list and the parameters of t_apply scenes.  Tables end with a
 * row whose name is NULL.
 *
 *   struct noise_params { double frequency; int octaves; };
 *   static const struct tex_param rows[] = {
 *       TEX_REAL(struct noise_params, frequency, 'f', 8, 0, 1e6, "F",
 *                "lattice cells across the map"),
 *       TEX_INT(struct noise_params, octaves, 0, 1, 1, 30, "N", "octaves"),
 *       {0}};
 *
 * Types:
 *   TEX_P_INT     int, range [min,max]
 *   TEX_P_REAL    double, range [min,max], NaN and infinity refused
 *   TEX_P_FLAG    int set to 1 by the option (no argument)
 *   TEX_P_ENUM    int index into choices "a|b|c"; defstr the default name
 *   TEX_P_REALS   struct tex_reals, 1..nmax comma-separated reals in [min,max]
 *   TEX_P_COLOR   float[4] RGBA from #rgb, #rrggbb, #rrggbbaa, r,g,b[,a] or one grey level in [0,1]
 *   TEX_P_STRING  const char * (pointing into argv or the scene)
 *   TEX_P_FLOAT   float, range [min,max], NaN and infinity refused
 *   TEX_P_SPECIAL no storage: the row's read callback parses it (a scene's
 *                 `facets beckmann 0.2`), as AVOption's custom types do; the
 *                 row gives its help, default and range
 *
 * INT, REAL and FLOAT rows may hold a vector: n values stored one after the
 * other (a tex_v3, an RGB float[3], int w, h).  counts is the mask of value
 * counts accepted (bit k: k values; 0 means exactly n); a single value
 * given where n are stored is copied to all n (a grey level for a colour).
 * Written as text, the values are separated by commas.
 *
 * kinds is for tables shared by several kinds of one block (lights, shapes):
 * bit k set if the row applies to kind k; 0 means every kind.
 *
 * Option names are the row names with '_' written as '-'.  Messages name a
 * parameter the way its caller writes it: "--octaves must be 1..30 (got '40')"
 * on the command line (tex_param_set), "octaves must be 1..30 (got 40)" in
 * scenes and scripts (tex_param_parse with TEX_PARAM_WORD).
 */
#ifndef TEX_PARAM_H
#define TEX_PARAM_H

#include "api.h"

#include <stddef.h>
#include <stdio.h>

TEX_API_BEGIN

struct tex_param;
/* A SPECIAL row's reader: reader is the caller's (a scene's parser, which has just taken the
 * row's word), ctx the block being read.  Errors go the reader's own way. */
typedef void tex_param_read(void *reader, const struct tex_param *p, void *ctx);

enum tex_ptype { TEX_P_INT, TEX_P_REAL, TEX_P_FLAG, TEX_P_ENUM, TEX_P_REALS, TEX_P_COLOR,
                 TEX_P_STRING, TEX_P_FLOAT, TEX_P_SPECIAL };

#define TEX_REALS_MAX 32
struct tex_reals {
    int n;
    double v[TEX_REALS_MAX];
};

struct tex_param {
    const char *name;   /* option and scene keyword; NULL ends a table */
    int key;            /* short option letter, or 0 */
    enum tex_ptype type;
    size_t off;         /* where the value lives in the struct */
    double def, min, max;
    const char *defstr; /* default for ENUM, REALS, COLOR, STRING (may be NULL) */
    const char *choices; /* ENUM: "fbm|ridged|hybrid" */
    int nmax;           /* REALS: most values accepted */
    const char *meta;   /* argument name shown in help: "F", "N", "LIST" */
    const char *help;
    int n;              /* INT, REAL, FLOAT: values stored (0: 1) */
    unsigned counts;    /* INT, REAL, FLOAT: value counts accepted, bit k for k (0: n) */
    unsigned kinds;     /* block kinds or modes the row applies to, bit k for kind k (0: all) */
    const char *alias;  /* another long name, documented: the thesis's letter ("h" for hurst) */
    const char *old;    /* deprecated names, still taken with a warning: "-d width" */
    tex_param_read *read; /* SPECIAL: parses the row's value */
    const char *bare;   /* ENUM: the value of the option given alone, as GNU's --color; the
                         * next word is its value only when it is one of the choices */
};

/* How messages name a parameter: as an option ("--major-radius") or as the
 * word of a scene or script ("major-radius"). */
enum tex_param_style { TEX_PARAM_OPTION, TEX_PARAM_WORD };

#define TEX_INT_N(name, S, f, k, d, lo, hi, meta, help, ...)                                     \
    {name, k, TEX_P_INT, offsetof(S, f), d, lo, hi, NULL, NULL, 0, meta, help, .n = 0,          \
     __VA_ARGS__}
#define TEX_INT(S, f, ...) TEX_INT_N(#f, S, f, __VA_ARGS__)
#define TEX_REAL_N(name, S, f, k, d, lo, hi, meta, help, ...)                                    \
    {name, k, TEX_P_REAL, offsetof(S, f), d, lo, hi, NULL, NULL, 0, meta, help, .n = 0,         \
     __VA_ARGS__}
#define TEX_REAL(S, f, ...) TEX_REAL_N(#f, S, f, __VA_ARGS__)
#define TEX_FLAG_N(name, S, f, k, help, ...)                                                     \
    {name, k, TEX_P_FLAG, offsetof(S, f), 0, 0, 1, NULL, NULL, 0, NULL, help, .n = 0, __VA_ARGS__}
#define TEX_FLAG(S, f, ...) TEX_FLAG_N(#f, S, f, __VA_ARGS__)
#define TEX_ENUM_N(name, S, f, k, def, choices, help, ...)                                       \
    {name, k, TEX_P_ENUM, offsetof(S, f), 0, 0, 0, def, choices, 0, NULL, help, .n = 0,         \
     __VA_ARGS__}
#define TEX_ENUM(S, f, ...) TEX_ENUM_N(#f, S, f, __VA_ARGS__)
#define TEX_REALS_N(name, S, f, k, def, lo, hi, nmax, meta, help, ...)                           \
    {name, k, TEX_P_REALS, offsetof(S, f), 0, lo, hi, def, NULL, nmax, meta, help, .n = 0,      \
     __VA_ARGS__}
#define TEX_REALS(S, f, ...) TEX_REALS_N(#f, S, f, __VA_ARGS__)
#define TEX_COLOR_N(name, S, f, k, def, help, ...)                                               \
    {name, k, TEX_P_COLOR, offsetof(S, f), 0, 0, 1, def, NULL, 0, "COLOUR", help, .n = 0,       \
     __VA_ARGS__}
#define TEX_COLOR(S, f, ...) TEX_COLOR_N(#f, S, f, __VA_ARGS__)
#define TEX_STRING_N(name, S, f, k, def, meta, help, ...)                                        \
    {name, k, TEX_P_STRING, offsetof(S, f), 0, 0, 0, def, NULL, 0, meta, help, .n = 0,          \
     __VA_ARGS__}
#define TEX_STRING(S, f, ...) TEX_STRING_N(#f, S, f, __VA_ARGS__)

/* A row is named after its field; the _N forms name it apart from the field
 * (TEX_REAL_N("slice", S, z, ...)).  Each macro takes designated initializers
 * after its arguments for the rest of the row: .kinds, .alias and .old, e.g.
 *   TEX_REALS(S, hurst, 0, "0.8", -1, 3, 32, "H", "Hurst exponent", .alias = "h")
 * A name in .old is a short option ("-d") or a long name ("width"): the
 * front end and tex_param_find take it and warn that it is deprecated. */

/* Rows of scenes, named apart from their field ("Ka" stored in ka): type T
 * (INT, REAL, FLOAT, FLAG), the default as text ("0.8", "0,0,-5"), n values
 * stored, counts accepted (0: n). */
#define TEX_ROW(name, S, f, T, d, lo, hi, nv, cnt, meta, help, ...)                              \
    {name, 0, T, offsetof(S, f), 0, lo, hi, d, NULL, 0, meta, help, .n = nv, .counts = cnt,     \
     __VA_ARGS__}
#define TEX_ROW_ENUM(name, S, f, d, choices, help, ...)                                          \
    {name, 0, TEX_P_ENUM, offsetof(S, f), 0, 0, 0, d, choices, 0, NULL, help, .n = 0, __VA_ARGS__}
/* A row read by its own callback (no storage). */
#define TEX_SPECIAL(name, lo, hi, def, meta, help, fn, ...)                                      \
    {name, 0, TEX_P_SPECIAL, 0, 0, lo, hi, def, NULL, 0, meta, help, .n = 0, .read = fn,        \
     __VA_ARGS__}

/* Store every row's default in obj (SPECIAL rows have none).  Returns -1
 * only for a broken table. */
int tex_params_defaults(const struct tex_param *t, void *obj);
/* Parse text as row p's value into obj; -1 with a usage error naming the
 * parameter and its valid range. */
int tex_param_set(const struct tex_param *p, void *obj, const char *text);
/* The same, with messages naming the parameter in the given style. */
int tex_param_parse(const struct tex_param *p, void *obj, const char *text,
                    enum tex_param_style style);
/* Store k numbers as row p's value (INT, REAL, FLOAT, FLAG: 0 or 1), checking
 * the count and the range: -1 with a usage error such as "fov must be
 * 0.01..179 (got 180)".  For readers that have numbers, not text. */
int tex_param_store(const struct tex_param *p, void *obj, const double *v, int k,
                    enum tex_param_style style);
/* Values stored by an INT, REAL or FLOAT row (1 for a scalar). */
int tex_param_count(const struct tex_param *p);
/* The last error in the words of scenes and scripts: every option name in
 * it ("--octaves", "--mf-offset") loses its dashes.  For checks written once
 * for every caller (a primitive's init), called when the caller is a scene
 * or a script. */
void tex_error_in_words(void);
/* The parameter's name in a style: "--major-radius" or "major-radius". */
const char *tex_param_name(const struct tex_param *p, char *buf, size_t n,
                           enum tex_param_style style);
/* The row called name, or NULL.  Names match with '-' or '_', in UK or US
 * spelling (colour/color, centre/center, grey/gray, quantise/quantize...),
 * and by the row's aliases; a row's old name matches with a warning
 * (tex_warning) that it is deprecated. */
const struct tex_param *tex_param_find(const struct tex_param *t, const char *name);
/* Are old names refused instead of warned about?  TEXTURA_DEPRECATED=error says
 * so, for checking that scripts use the current names. */
int tex_param_deprecated_is_error(void);
/* The next word of a row's space-separated name list (.alias, .old) into word,
 * advancing *list; NULL at the end.  Words longer than n are skipped. */
const char *tex_param_list_next(const char **list, char *word, size_t n);
/* The name of the row of t (of kind kind, or any for -1) nearest to a mistyped word, for a
 * message's "did you mean", or NULL when none is near (base/nearest.h's rule). */
const char *tex_param_nearest(const struct tex_param *t, int kind, const char *word, char *buf,
                              size_t n);
/* The word of choices ("add|sub|mul") nearest to a mistyped word, or NULL (the same rule). */
const char *tex_choice_nearest(const char *choices, const char *word, char *buf, size_t n);
/* Do two names match as tex_param_find matches them ('-' or '_', UK or US)? */
int tex_param_same_name(const char *a, const char *b);
/* name in US spelling with '-' for '_' ("colour1" -> "color1"), into buf. */
const char *tex_param_us_spelling(const char *name, char *buf, size_t n);
/* The valid range or choices as text, e.g. "1..30" or "fbm|ridged". */
const char *tex_param_range(const struct tex_param *p, char *buf, size_t n);
/* The default as text, e.g. "8" or "#ff8000". */
const char *tex_param_default(const struct tex_param *p, char *buf, size_t n);
/* The option spelling of a row name: "--major-radius". */
const char *tex_param_option(const struct tex_param *p, char *buf, size_t n);

/* Helpers for values that are not whole rows. */
int tex_parse_real(const char *text, double *out);         /* -1 if not a finite number */
int tex_parse_color(const char *text, float rgba[4]);      /* -1 if malformed */
int tex_parse_size(const char *text, int *w, int *h);      /* N or WxH; -1 outside the map limits */

TEX_API_END
#endif
