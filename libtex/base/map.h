/* map.h - the texture map: one sampled texture field as an image
 *
 * A texture map is width x height pixels of 1 to 4 float32 channels,
 * interleaved, row-major, top row first (v grows downwards, as the thesis
 * numbers subregions left to right, top to bottom).  1 channel is a scalar
 * field, 2 a vector (e.g. a gradient), 3 RGB, 4 RGBA.
 *
 * Metadata travels with the map: the number of subregions when the map
 * holds region ids (0 otherwise), and the history, the command lines that
 * made it, one per line; and, for a window of a larger map (a generator's
 * --window, a region of a render), its place: the window's top-left pixel
 * (x0, y0) in the full_w x full_h map (full_w 0: the map is whole).  EXR
 * carries the place as the data window inside the display window.
 *
 *   tex_map *m = tex_map_new(256, 256, 1);   // NULL and tex_errmsg() on failure
 *   tex_map_px(m, x, y)[c] = 0.5f;
 *   tex_map_free(m);
 *
 * Sizes are checked without overflow: each side must be 1..TEX_MAP_MAX_SIDE,
 * and a map held whole at most TEX_MAP_MAX_SAMPLES floats (4 GiB).  A map that
 * passes through a pipeline in bands of rows is never held whole: its sides
 * alone are checked (tex_map_check_sides), up to 65536 x 65536 x 4.
 */
#ifndef TEX_MAP_H
#define TEX_MAP_H

#include "api.h"

#include <stddef.h>

TEX_API_BEGIN

#define TEX_MAP_MAX_SIDE 65536
#define TEX_MAP_MAX_SAMPLES (1ULL << 30)
/* The rule for a map's size in pixels, as messages say it where a size is refused (-s) */
#define TEX_MAP_SIZE_RULE "each side 1..65536"
#define TEX_MAP_MAX_CHANNELS 4

typedef struct tex_map {
    int w, h, nc;
    float *px;      /* w*h*nc floats, 64-byte aligned */
    int subregions; /* > 0: the pixels are region ids 1..subregions */
    char *history;  /* command lines, newline-terminated; NULL if none */
    int x0, y0, full_w, full_h; /* a window's place in the full map; full_w 0: whole */
    size_t mapped;  /* private: bytes mmap'ed for px, 0 if malloc'ed */
} tex_map;

/* bytes of zeroed memory, 64-byte aligned, for a buffer a caller fills: from min bytes up
 * (and 1), fresh pages (in 2 MiB huge pages where the kernel gives them: a first touch of each
 * 4 KiB page is a page fault), else the heap.
 * *mapped is what tex_pages_free takes back (0 from the heap); NULL when out of memory.
 * tex_pages_free keeps a few mappings up to 64 MiB for the next tex_pages_new of their size. */
void *tex_pages_new(size_t bytes, size_t min, size_t *mapped);
/* tex_pages_new's pages p (mapped bytes) made present, zeroed, now: their first touch paid
 * where they are made, not where the caller writes them (a render's inner loop) */
void tex_pages_touch(void *p, size_t mapped);
void tex_pages_free(void *p, size_t mapped);
/* For tools, at start (tex_cli_parse): with glibc, memory freed stays on the heap for the
 * next allocation instead of going back to the system, so that buffers of one size made
 * again and again (a band, zlib's state for each compressed chunk, an FFT's spectrum)
 * reuse touched pages instead of faulting in fresh ones.
 * tex_pages_new's mappings are not the heap's. Does nothing elsewhere. */
void tex_keep_heap(void);

/* 0 if a w x h x nc map may be held whole, else -1 with a usage error naming the limit. */
int tex_map_check_size(long long w, long long h, long long nc);
/* 0 if a w x h x nc map may pass in bands (its sides and channels), else -1 likewise. */
int tex_map_check_sides(long long w, long long h, long long nc);

tex_map *tex_map_new(int w, int h, int nc); /* zero-filled */
/* A map whose samples are what its memory held, for a caller that sets every one: from 1 MiB
 * a mapping freed before may come back, without the pass that zeroes it */
tex_map *tex_map_new_unset(int w, int h, int nc);
void tex_map_free(tex_map *m);
tex_map *tex_map_clone(const tex_map *m);

/* A map made from src carries src's history (and its place in a full map when
 * both are the same size); returns -1 on allocation failure. */
int tex_map_inherit(tex_map *dst, const tex_map *src);
/* Only the place in a full map (same size only). */
void tex_map_inherit_place(tex_map *dst, const tex_map *src);
/* Append one line to the history; returns -1 on allocation failure. */
int tex_map_add_history(tex_map *m, const char *line);
int tex_map_set_history(tex_map *m, const char *history);

static inline float *tex_map_row(const tex_map *m, int y)
{
    return m->px + (size_t)y * m->w * m->nc;
}

static inline float *tex_map_px(const tex_map *m, int x, int y)
{
    return m->px + ((size_t)y * m->w + x) * m->nc;
}

static inline size_t tex_map_samples(const tex_map *m)
{
    return (size_t)m->w * m->h * m->nc;
}

/* How a lookup beyond a map's edge is answered: the border pixel (clamp), the
 * opposite side (wrap: a tileable map stays tileable), the mirror image, or
 * nothing (background: the caller supplies a colour).  The order is that of
 * the options "clamp|wrap|mirror". */
enum tex_edge { TEX_EDGE_CLAMP, TEX_EDGE_WRAP, TEX_EDGE_MIRROR, TEX_EDGE_BACKGROUND };

/* The index in 0..n-1 that position i (any integer) reads, or -1 for background. */
static inline long tex_edge_index(long i, long n, enum tex_edge e)
{
    if (i >= 0 && i < n)
        return i;
    switch (e) {
    case TEX_EDGE_CLAMP:
        return i < 0 ? 0 : n - 1;
    case TEX_EDGE_WRAP:
        i %= n;
        return i < 0 ? i + n : i;
    case TEX_EDGE_MIRROR:
        i %= 2 * n;
        if (i < 0)
            i += 2 * n;
        return i < n ? i : 2 * n - 1 - i;
    default:
        return -1;
    }
}

/* The next level of a mip-map pyramid: floor(w/2) x floor(h/2) (at least 1),
 * as OpenEXR's round-down levels; each pixel is the mean of the fx x fy
 * pixels from its corner, fx = w / floor(w/2) (a box filter; a remainder
 * column or row at the far edge is dropped).  The renderer's pyramid and
 * EXR --mipmap files are built by this one function. */
tex_map *tex_map_reduce(const tex_map *s);

/* Parse "X,Y,W,H" (decimal integers) as a window of a full_w x full_h map
 * into r[0..3]: 0, or -1 when malformed, of zero size or not wholly inside. */
int tex_parse_window(const char *text, int full_w, int full_h, int r[4]);

/* Statistics of one channel over its finite samples (0 when it has none); nonfinite counts
 * NaN and infinities, nan the NaN among them (as oiiotool --stats counts them apart). */
struct tex_stats {
    double min, max, mean, stddev;
    size_t nonfinite, nan;
};
void tex_map_stats(const tex_map *m, int channel, struct tex_stats *s);

/* The same statistics gathered as rows pass (a stream), in one pass: each row's samples are
 * summed in four lanes (x mod 4) met in a fixed order, and the rows' sums in the map's
 * order, so the figures do not depend on how the rows were split.  The mean is that sum of
 * the samples over their count; the deviation is taken from sums
 * about the mean of the first row that has a finite sample, which keeps it as exact as a
 * second pass about the mean would.
 *
 *   struct tex_stats_acc a[4];
 *   for (c...) tex_stats_begin(&a[c]);
 *   for each band: tex_stats_add(&a[c], band + c, pixels_per_row, rows, nc);
 *                  (or tex_stats_add_pixels(a, band, pixels_per_row, rows, nc))
 *   tex_stats_end(&a[c], &s); */
struct tex_stats_acc {
    double sum, shift, s1, s2;
    float lo, hi;
    size_t n, nonfinite, nan;
    int shifted; /* the shift is set */
};
void tex_stats_begin(struct tex_stats_acc *a);
/* Add rows of w samples each, nc floats apart (px: the channel's first sample). */
void tex_stats_add(struct tex_stats_acc *a, const float *px, size_t w, size_t rows, int nc);
/* The same for every channel at once: a[c] takes channel c of rows of w pixels of nc
 * channels (px: the first pixel), as tex_stats_add(&a[c], px + c, ...) would. */
void tex_stats_add_pixels(struct tex_stats_acc *a, const float *px, size_t w, size_t rows, int nc);
/* Only the range: of tex_stats_end's figures, min and max hold and no others (a palette's
 * auto range), without the sums' cost. */
void tex_stats_add_range(struct tex_stats_acc *a, const float *px, size_t w, size_t rows, int nc);
void tex_stats_end(const struct tex_stats_acc *a, struct tex_stats *s);

TEX_API_END
#endif

