/* palette.h - palettes: scalars and region ids to colours
 *
 * A palette maps a scalar t in [0,1] to a colour through gradient stops,
 * interpolated in linear RGB or in OKLab, and a region id (the subregions
 * of the geometric primitives) to an indexed colour.  Palettes are small
 * text files; the format is in textura-palette(5):
 *
 *   # wood.pal
 *   space oklab
 *   0    #4a2a10
 *   0.6  0.62 0.40 0.18
 *   1    #d9a66b
 *   index 1 #ffffff
 *
 *   tex_palette *p = tex_palette_load("marble");   // NULL + tex_errmsg()
 *   float c[4];
 *   tex_palette_lookup(p, 0.25f, c);               // gradient at t (clamped to [0,1])
 *   tex_palette_index(p, 3, c);                    // colour of region 3
 *   tex_palette_free(p);
 *
 * Names: a name containing '/' or ending in ".pal" is a file.  Any other
 * name ("marble") is looked up as NAME.pal in, in order: each folder of
 * $TEXTURA_PALETTES (colon-separated), then the palettes/ folder of the
 * install's data folder, found at run time (base/paths.h; a build tree's
 * build/share/textura links to the source tree's palettes/).
 *
 * Colour values are stored as given (display values in [0,1], no transfer
 * function), as maps are.  OKLab interpolation treats them as sRGB-encoded:
 * it decodes to linear light, interpolates in OKLab and encodes again, which
 * gives perceptually even steps.  At a stop's position the lookup returns
 * the stop's colour exactly.
 *
 * Region ids: an id with its own `index` line gets that colour.  Other ids
 * take colours from the gradient: tex_palette_index_n(p, id, n, c) spreads
 * ids 1..n evenly over [0,1]; tex_palette_index (n unknown) uses the golden
 * ratio sequence t = frac(id * 0.618...), so neighbouring ids differ.
 *
 * Colouring a whole map:
 *
 *   tex_map *c = tex_palette_map(p, m, lo, hi, TEX_OUTSIDE_CLAMP);
 *
 * A scalar map (1 channel) becomes RGB, or RGBA when the palette has any
 * alpha below 1: t = (v - lo) / (hi - lo), and values outside [lo,hi]
 * clamp, repeat (sawtooth) or mirror (triangle wave).  lo = hi = NaN picks
 * the map's own finite minimum and maximum.  A region-id map (subregions
 * > 0) takes indexed colours: tex_palette_index_n(p, id, subregions).
 *
 * Errors (a bad file, an unknown name) are reported with file:line through
 * tex_error() (runtime, exit 1); an unknown palette name is a usage error.
 */
#ifndef TEX_PALETTE_H
#define TEX_PALETTE_H

#include "../base/api.h"

#include <stddef.h>
#include <stdio.h>

TEX_API_BEGIN

enum tex_palette_space { TEX_SPACE_RGB, TEX_SPACE_OKLAB };

struct tex_palette_stop {
    float pos;     /* 0..1, non-decreasing; two equal positions make a hard edge */
    float rgba[4]; /* as written in the file */
    float lab[4];  /* OKLab + alpha, for interpolation in OKLab */
};

struct tex_palette_entry {
    int id;
    float rgba[4];
};

typedef struct tex_palette {
    char *name;                     /* the name or file it came from */
    enum tex_palette_space space;
    int nstops;
    struct tex_palette_stop *stops;
    int nindex;                     /* indexed colours, sorted by id */
    struct tex_palette_entry *index;
} tex_palette;

/* Load a palette by name or file (see above). */
tex_palette *tex_palette_load(const char *name_or_file);
/* Parse palette text; name is used in messages ("name:line: ..."). */
tex_palette *tex_palette_parse(const char *text, size_t len, const char *name);
/* An empty palette to fill with tex_palette_add_stop (for generated palettes). */
tex_palette *tex_palette_new(enum tex_palette_space space);
int tex_palette_add_stop(tex_palette *p, float pos, const float rgba[4]);
void tex_palette_free(tex_palette *p);

/* Write p in the text format; values round-trip exactly.  -1 on a write error. */
int tex_palette_write(const tex_palette *p, FILE *fp);

/* The file a name resolves to, in buf; -1 with a usage error if none exists
 * (it lists the known names). */
int tex_palette_find(const char *name, char *buf, size_t n);
/* The names of the palettes found in the search path, sorted, comma-separated
 * in buf (truncated to n); returns how many there are. */
int tex_palette_names(char *buf, size_t n);

void tex_palette_lookup(const tex_palette *p, float t, float rgba[4]);
/* tex_palette_lookup at n positions t in [0, 1] (as tex_palette_t gives them) into rgb, three
 * floats each: the same floats, the colours mixed in OKLab taken to sRGB together (in
 * vector lanes where the CPU has them) */
void tex_palette_lookup_n(const tex_palette *p, const float *t, int n, float *rgb);
void tex_palette_index(const tex_palette *p, int id, float rgba[4]);
void tex_palette_index_n(const tex_palette *p, int id, int n, float rgba[4]);
/* The colours of subregions 1..n (tex_palette_index_n): n RGB triples from
 * malloc, for a REGIONS field's colors (prim.h); NULL when memory fails. */
float *tex_palette_region_colours(const tex_palette *p, int n);

struct tex_map;
enum tex_outside { TEX_OUTSIDE_CLAMP, TEX_OUTSIDE_REPEAT, TEX_OUTSIDE_MIRROR };
/* Colour a map; NULL + tex_error() if it is not a scalar map or memory fails. */
struct tex_map *tex_palette_map(const tex_palette *p, const struct tex_map *m, double lo,
                                double hi, enum tex_outside outside);
/* The position in [0,1] of value v for range [lo,hi] and an outside mode. */
float tex_palette_t(double v, double lo, double hi, enum tex_outside outside);

/* Colour spaces: sRGB-encoded RGB (alpha untouched) <-> OKLab. */
void tex_srgb_to_oklab(const float rgb[3], float lab[3]);
void tex_oklab_to_srgb(const float lab[3], float rgb[3]);

TEX_API_END
#endif
