/* prim.h - the primitive descriptor: one description, two modalities
 *
 * A primitive ("primitiva de textura") is a parametrised generator of a
 * texture field.  Its descriptor, a struct tex_primitive, is the one place
 * that declares it: name, one-line summary, parameter table (param.h) and
 * evaluation callbacks.  From it
 *   - the tool t_NAME samples the field on a grid and writes the map
 *     (its main is one call: tex_generate_main(&tex_prim_NAME, argc, argv));
 *   - --help and the man page list the parameters with defaults and ranges;
 *   - t_apply scenes name the primitive and its parameters and evaluate it
 *     at hit points (solid textures need eval3).
 *
 * Kinds, in flags:
 *   TEX_PRIM_2D       eval2 at any (u,v) points
 *   TEX_PRIM_3D       eval3 at any (u,v,w) points: a solid texture
 *   TEX_PRIM_GRID     grid fills a whole map at once (midpoint displacement,
 *                     spectral synthesis...); the renderer uses the map
 *   TEX_PRIM_REGIONS  values are subregion ids 1..nregions
 *   TEX_PRIM_TILE     honours tile: the field is periodic over the unit square
 *
 * Texture space is [0,1]^2 (or ^3); sampling a w x h map evaluates pixel
 * (x,y) at u = (x+0.5)/w, v = (y+0.5)/h, with v growing downwards.  Points
 * come a row at a time so that inner loops vectorise; out receives n
 * values of nc floats each, interleaved.  Evaluation must be a pure
 * function of the point and the field, so that any thread split gives the
 * same bytes.
 *
 * Windows: tex_field_window before tex_field_init makes tex_field_sample
 * fill only columns wx..wx+ww-1 and rows wy..wy+wh-1 of the w x h grid,
 * bit-identical to the same pixels of the whole map (every pixel is still
 * evaluated at its place in the whole grid).  Point and row primitives
 * window for free; a grid primitive windows through its row callback, or
 * says why it cannot in whole(); one without either refuses.
 *
 * Registering a primitive: define `const struct tex_primitive tex_prim_NAME`
 * in its module and add TEX_PRIMITIVE(NAME) to primitives.def.
 */
#ifndef TEX_PRIM_H
#define TEX_PRIM_H

#include <stdint.h>

#include "../base/api.h"
#include "../base/map.h"
#include "../base/param.h"

TEX_API_BEGIN

enum {
    TEX_PRIM_2D = 1 << 0,
    TEX_PRIM_3D = 1 << 1,
    TEX_PRIM_GRID = 1 << 2,
    TEX_PRIM_REGIONS = 1 << 3,
    TEX_PRIM_TILE = 1 << 4,
};

struct tex_field {
    const struct tex_primitive *prim;
    void *params;     /* the primitive's parameter struct, defaults filled in */
    uint64_t seed;
    int tile;         /* 1: periodic over the unit square / cube */
    int ids;          /* 1: REGIONS primitives write region ids, not colours */
    int w, h;         /* the grid being sampled (0 when evaluated at points) */
    long queries;     /* at points: how many the caller will ask, when it knows (0: unknown);
                       * sizes search tables as a grid's w * h does */
    int nc;           /* floats per value; init may change it (default 1) */
    int nregions;     /* REGIONS: set by init */
    /* REGIONS: the colour of region k is colors[k-1] (init or a palette sets
     * it).  When set and ids is 0, the sampler writes an RGB map in which each
     * pixel is the mean colour of TEX_FIELD_SS x TEX_FIELD_SS stratified
     * subsamples (antialiasing by coverage; with box2, only pixels an edge may
     * cross are subsampled, and with ids only the centres box2 leaves unsure
     * are evaluated); eval2 still writes one id per point. */
    const float (*colors)[3];
    void *state;      /* the primitive's own, made by init */
    int wx, wy, ww, wh; /* the window being sampled (tex_field_window); ww 0: the whole grid */
    int size;         /* a scene's or script's `size N`: sample on an N x N grid (0: none) */
    int band_limit;   /* set by init: eval3_fw fades octaves finer than a footprint */
    enum tex_param_style style; /* how init's messages name parameters: TEX_PARAM_OPTION
                                 * (tools, the default) or TEX_PARAM_WORD (scenes, scripts) */
};

/* The texture-level fields of every primitive, declared once: the tools'
 * -S/--seed, --tile, --ids and -s, a scene's texture block and a script's
 * primitive call read them through these rows, with one limit each:
 *   seed  0..2147483647 (TEX_SEED_MAX); default 1 in tools, 0 in scenes and scripts
 *   tile  flag (0 or 1 in a script)
 *   ids   flag (0 or 1 in a script)
 *   size  1..65536 a side (TEX_MAP_MAX_SIDE): N or WxH in tools, N in scenes
 *         and scripts (a script's `W by H` has the same limit)
 * The macros give a row over any struct, so that tools keep their own. */
#define TEX_SEED_MAX 2147483647
#define TEX_XSTR_(x) #x
#define TEX_XSTR(x) TEX_XSTR_(x)
#define TEX_SEED_ROW(S, f, k, d) TEX_INT(S, f, k, d, 0, TEX_SEED_MAX, "N", "random seed")
#define TEX_TILE_ROW(S, f)                                                                       \
    TEX_FLAG(S, f, 0, "make the map tile seamlessly left-right and top-bottom")
#define TEX_IDS_ROW(S, f)                                                                        \
    TEX_FLAG(S, f, 0, "write the subregion id of each pixel instead of colours")
#define TEX_SIZE_HELP "size of the map in pixels, N x N or W x H: " TEX_MAP_SIZE_RULE
struct tex_field_opts {
    int seed, tile, ids, size;
};
extern const struct tex_param tex_field_rows[]; /* over struct tex_field_opts */
/* A parameter named by its row, for messages (an init's checks, which tex_field_init turns
 * into a scene's words): the option of the row of rows that stores its value at offset off
 * ("--ring-width" for a ring's width), into buf.  So a message names the current option,
 * never an old name the row still takes.  TEX_OPTION(rows, S, field) gives it a buffer of
 * its own (alive to the end of the statement's block); TEX_FIELD_OPTION(tile) is "--tile". */
const char *tex_rows_option(const struct tex_param *rows, size_t off, char *buf, size_t n);
#define TEX_OPTION(rows, S, f) tex_rows_option(rows, offsetof(S, f), (char[64]){""}, 64)
#define TEX_FIELD_OPTION(f) TEX_OPTION(tex_field_rows, struct tex_field_opts, f)

struct tex_primitive {
    const char *name;    /* "noise": the tool is t_noise, the scene word is noise */
    const char *summary; /* one line, no final period */
    unsigned flags;
    size_t params_size;
    const struct tex_param *params;
    /* Check parameters that depend on each other and build tables (from the
     * seed).  Return -1 with tex_usage_error() for bad parameters. */
    int (*init)(struct tex_field *f);
    void (*fini)(struct tex_field *f);
    void (*eval2)(const struct tex_field *f, int n, const double *u, const double *v, float *out);
    void (*eval3)(const struct tex_field *f, int n, const double *u, const double *v,
                  const double *w, float *out);
    /* Optional, 3D: eval3 at points each seen through a footprint fw[i] texture
     * units wide (t_apply's solid textures, when init set f->band_limit): octaves
     * finer than the footprint fade to their mean.  With every fw[i] 0 it is eval3,
     * bit for bit. */
    void (*eval3_fw)(const struct tex_field *f, int n, const double *u, const double *v,
                     const double *w, const double *fw, float *out);
    /* Optional, REGIONS: out[i] = the region id that every point of the box
     * u[i] +- hu, v[i] +- hv has (eval2's id there, bit for bit), proven with a
     * margin above rounding, else 0 (unsure); hu or hv may be 0 (a row of
     * points, or one).  The sampler gives a proven span or pixel its region's
     * colour, or with ids its id, and evaluates only the others: the same bytes
     * as S x S subsamples, or every centre, everywhere. */
    void (*box2)(const struct tex_field *f, int n, const double *u, const double *v, double hu,
                 double hv, float *out);
    /* Optional fast path for grid sampling: row y of the f->w x f->h grid. */
    void (*row)(const struct tex_field *f, int y, float *out);
    /* Optional, beside row: rows y and y + 1 (n = 2) into out, the second f->w f->nc floats
     * on, row's bytes: rows that share work made together (an octave sum reads each
     * column's data once for both). */
    void (*rows)(const struct tex_field *f, int y, int n, float *out);
    /* TEX_PRIM_GRID: fill m (f->w x f->h, f->nc channels). */
    int (*grid)(const struct tex_field *f, tex_map *m);
    /* Optional, for GRID primitives with a row callback: NULL when this field
     * (its parameters) can be made a window at a time through rows, else why
     * it must be made whole, e.g. "midpoint displacement makes the whole map". */
    const char *(*whole)(const struct tex_field *f);
};

/* Every registered primitive: tex_prim_NAME, and the NULL-terminated list. */
#define TEX_PRIMITIVE(n) extern const struct tex_primitive tex_prim_##n;
#include "primitives.def"
#undef TEX_PRIMITIVE
extern const struct tex_primitive *const tex_primitives[];
/* The primitive called name; NULL with a usage error listing the known ones. */
const struct tex_primitive *tex_primitive_find(const char *name);
/* The same without the message, for a name that may be no primitive. */
const struct tex_primitive *tex_primitive_get(const char *name);
/* The registered primitive's name nearest to a mistyped one, into buf; NULL if none is near. */
const char *tex_primitive_nearest(const char *name, char *buf, size_t n);

/* A field with the primitive's defaults; NULL on allocation failure. */
struct tex_field *tex_field_new(const struct tex_primitive *p);
/* Set parameter name (option spelling or row name) from text: one of the
 * primitive's, or seed, tile, ids or size (tex_field_rows).  Messages name
 * it as scenes and scripts do: "octaves must be 1..30 (got 40)". */
int tex_field_set(struct tex_field *f, const char *name, const char *value);
/* Sample only the window of w x h pixels at (x, y) of the grid that init is
 * given: 0, or -1 with a usage error when the primitive cannot window (call
 * before tex_field_init; the caller checks that the window lies in the grid). */
int tex_field_window(struct tex_field *f, int x, int y, int w, int h);
/* NULL when the field can be sampled a window at a time, else why not. */
const char *tex_field_whole(const struct tex_field *f);
/* Run init once the parameters are set; w, h may be 0 outside a grid. */
int tex_field_init(struct tex_field *f, int w, int h);
void tex_field_free(struct tex_field *f);

/* Subsamples per pixel side when a REGIONS field is sampled in colour. */
#define TEX_FIELD_SS 4

/* Sample an initialised field on its w x h grid (or its window), threads from OpenMP. */
tex_map *tex_field_sample(const struct tex_field *f);
/* The channels of the maps it makes: 3 for regions in colour, else f->nc. */
int tex_field_channels(const struct tex_field *f);
/* tex_field_sample into m, a zero-filled map of the grid's (or window's) size and the
 * field's channels whose pixels may be the caller's (a band an encoder writes): 0, or -1
 * with an error. */
int tex_field_sample_into(const struct tex_field *f, tex_map *m);
/* tex_field_sample's rows for a primitive with a row callback, into m (its w x h grid,
 * no window): the same rows, made the same way, into a map made once (a benchmark's fills). */
int tex_field_sample_rows(const struct tex_field *f, tex_map *m);

TEX_API_END
#endif
