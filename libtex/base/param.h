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
 *   TEX_P_COLOR   float[4] RGBA from #rgb, #rrggbb, #rrggbbaa or r,g,b[,a] in [0,1]
 *   TEX_P_STRING  const char * (pointing into argv or the scene)
 *
 * Option names are the row names with '_' written as '-'.
 */
#ifndef TEX_PARAM_H
#define TEX_PARAM_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

enum tex_ptype { TEX_P_INT, TEX_P_REAL, TEX_P_FLAG, TEX_P_ENUM, TEX_P_REALS, TEX_P_COLOR,
                 TEX_P_STRING };

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
};

#define TEX_INT(S, f, k, d, lo, hi, meta, help)                                                  \
    {#f, k, TEX_P_INT, offsetof(S, f), d, lo, hi, NULL, NULL, 0, meta, help}
#define TEX_REAL(S, f, k, d, lo, hi, meta, help)                                                 \
    {#f, k, TEX_P_REAL, offsetof(S, f), d, lo, hi, NULL, NULL, 0, meta, help}
#define TEX_FLAG(S, f, k, help) {#f, k, TEX_P_FLAG, offsetof(S, f), 0, 0, 1, NULL, NULL, 0, NULL, help}
#define TEX_ENUM(S, f, k, def, choices, help)                                                   \
    {#f, k, TEX_P_ENUM, offsetof(S, f), 0, 0, 0, def, choices, 0, NULL, help}
#define TEX_REALS(S, f, k, def, lo, hi, nmax, meta, help)                                        \
    {#f, k, TEX_P_REALS, offsetof(S, f), 0, lo, hi, def, NULL, nmax, meta, help}
#define TEX_COLOR(S, f, k, def, help)                                                           \
    {#f, k, TEX_P_COLOR, offsetof(S, f), 0, 0, 1, def, NULL, 0, "COLOUR", help}
#define TEX_STRING(S, f, k, def, meta, help)                                                    \
    {#f, k, TEX_P_STRING, offsetof(S, f), 0, 0, 0, def, NULL, 0, meta, help}

/* Store every row's default in obj.  Returns -1 only for a broken table. */
int tex_params_defaults(const struct tex_param *t, void *obj);
/* Parse text as row p's value into obj; -1 with a usage error naming the
 * parameter and its valid range. */
int tex_param_set(const struct tex_param *p, void *obj, const char *text);
/* The row called name (with '-' or '_'), or NULL. */
const struct tex_param *tex_param_find(const struct tex_param *t, const char *name);
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

#ifdef __cplusplus
}
#endif
#endif
