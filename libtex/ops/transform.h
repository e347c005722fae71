/* transform.h - filtered geometric transforms of texture maps
 *
 * Rotate, scale, shift, expand and clip a map (thesis 4.3.2 and 5.2.4.2:
 * Rotate alpha, Scale dx dy, Shift dx dy, expand ... background, clipping).
 * Resampling is area-filtered: each output pixel averages an N x M grid of
 * bilinear lookups spread over its footprint in the source, N and M being
 * the number of source pixels the footprint spans along each axis (1 at
 * 1:1 or when magnifying), so a rotated or shrunk checkerboard does not
 * alias.  Maps that hold region ids (subregions > 0)
 * are sampled nearest-neighbour instead: ids must not be blended.
 *
 * Coordinates are in pixels of the source, pixel (x,y) covering
 * [x,x+1) x [y,y+1); angles are degrees, positive turns counter-clockwise
 * as seen on the screen (v grows downwards).  Where a transform uncovers
 * the canvas it shows the background colour (RGBA, 0..1): a 1-channel map
 * takes its first component, a 3-channel map its RGB; a background that
 * is not opaque gives the result an alpha channel (4 channels).
 *
 *   float bg[4] = {0, 0, 0, 1};
 *   tex_map *r = tex_rotate(m, 20, 150, 150, bg);     // NULL + tex_errmsg()
 *   tex_map *s = tex_resize(m, m->w / 3, m->h / 3);   // filtered shrink
 *   tex_map *c = tex_clip(r, 50, 50, 250, 250);       // 200 x 200 window
 *
 * The low-level sampler serves the other composition modules (tiling,
 * warping): tex_sample() returns the filtered value at a point given its
 * footprint, with an edge rule for lookups outside the map.
 */
#ifndef TEX_TRANSFORM_H
#define TEX_TRANSFORM_H

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

struct tex_sampler {
    const tex_map *m;
    enum tex_edge edge;
    float bg[4];  /* background in m's channel layout (TEX_EDGE_BACKGROUND) */
    int nearest;  /* 1: no interpolation or averaging (region ids) */
    int maxtaps;  /* most lookups per axis for one output pixel (0: 32) */
    int row0, rows; /* m holds rows row0.. of a map rows tall, counted modulo rows (a band
                     * may wrap past the last row; -rows < row0 < rows; init: 0, m->h) */
    int level;    /* the SIMD level tex_sample's code takes (init: tex_simd_level(); same floats) */
};

/* A band of a map's rows: band holds rows row0..row0 + band->h - 1 of a map full_h rows
 * tall, counted modulo full_h (-full_h < row0 < full_h), so a band may wrap from the last
 * row to the first, as a sampler with a wrapping edge rule reads it. */
struct tex_map_rows {
    const tex_map *band;
    int row0, full_h;
};

/* Prepare a sampler; bg is RGBA and is converted to m's channels. */
void tex_sampler_init(struct tex_sampler *s, const tex_map *m, enum tex_edge edge,
                      const float bg[4]);
/* The filtered value at source point (x,y) (pixels) whose output pixel
 * spans the source vectors du = (du[0],du[1]) and dv: out gets m->nc floats. */
void tex_sample(const struct tex_sampler *s, double x, double y, const double du[2],
                const double dv[2], float *out);

/* Channels of the result of drawing m over background bg (RGBA). */
int tex_bg_channels(const tex_map *m, const float bg[4]);
/* A copy of m with nc channels: 1 -> 3 (grey), 1/3 -> 4 (opaque), 4 -> 3
 * (drop alpha), 3/4 -> 1 (Rec. 709 luminance); other pairs fail. */
tex_map *tex_map_channels(const tex_map *m, int nc);

/* The general case: a w x h map whose pixel centre (X,Y) samples m at
 * x = a[0] X + a[1] Y + a[2], y = a[3] X + a[4] Y + a[5]. */
tex_map *tex_affine(const tex_map *m, int w, int h, const double a[6], enum tex_edge edge,
                    const float bg[4]);
/* Rows y..y + out->h - 1 of tex_affine(M, out->w, h, a, edge, bg) into out (its
 * channels tex_bg_channels'), made from band, which holds rows row0..row0 + band->h - 1 of
 * M, a map full_h rows tall and band->w wide: the whole map's values, bit for bit, where
 * band holds every row of M inside 0..full_h - 1 that tex_affine_reads names.  The way a
 * transform streams (t_xform).  0, or -1 with the error set. */
int tex_affine_rows(const tex_map *band, int row0, int full_h, tex_map *out, int y,
                    const double a[6], enum tex_edge edge, const float bg[4]);
/* The rows [*from, *to) of M that rows y..y+n-1 of an affine w pixels wide read, before
 * the edge rule (they may pass M's edges) */
void tex_affine_reads(const double a[6], int w, int y, int n, long *from, long *to);

tex_map *tex_rotate(const tex_map *m, double degrees, double cx, double cy, const float bg[4]);
tex_map *tex_resize(const tex_map *m, int w, int h);
tex_map *tex_scale(const tex_map *m, double sx, double sy); /* to round(w sx) x round(h sy) */
/* Move the content by (dx,dy) pixels; wrap: re-enter at the other side. */
tex_map *tex_shift(const tex_map *m, double dx, double dy, int wrap, const float bg[4]);
/* A w x h canvas of bg with m centred on it (m is cropped if larger). */
tex_map *tex_expand(const tex_map *m, int w, int h, const float bg[4]);
/* The window [x0,x1) x [y0,y1), which must lie inside m. */
tex_map *tex_clip(const tex_map *m, int x0, int y0, int x1, int y1);

/* Each transform above as the affine it is: the output's size, tex_affine's a, the edge
 * rule and background (bg is kept, not copied) of the step on a w x h map, 0 or -1 with the
 * error set as the transform itself would fail; tex_step applies one.  A chain of steps
 * can then stream, a band of rows at a time (tex_affine_rows, t_xform). */
struct tex_xstep {
    int w, h;
    double a[6];
    enum tex_edge edge;
    const float *bg;
};
tex_map *tex_step(const tex_map *m, const struct tex_xstep *st);
int tex_rotate_step(int w, int h, double degrees, double cx, double cy, const float bg[4],
                    struct tex_xstep *st);
int tex_resize_step(int w, int h, int ow, int oh, struct tex_xstep *st);
int tex_scale_step(int w, int h, double sx, double sy, struct tex_xstep *st);
void tex_shift_step(int w, int h, double dx, double dy, int wrap, const float bg[4],
                    struct tex_xstep *st);
int tex_expand_step(int w, int h, int ow, int oh, const float bg[4], struct tex_xstep *st);
int tex_clip_step(int w, int h, int x0, int y0, int x1, int y1, struct tex_xstep *st);

TEX_API_END
#endif
