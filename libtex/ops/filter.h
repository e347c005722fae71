/* filter.h - neighbourhood filters on texture maps (thesis 4.3.2, general tools)
 *
 * Every filter reads a map and returns a new one (NULL + tex_errmsg() on
 * failure); the input is untouched.  Pixels beyond the border come from the
 * edge mode: TEX_EDGE_CLAMP repeats the border pixel, TEX_EDGE_WRAP takes
 * the opposite side (a tileable map stays tileable), TEX_EDGE_MIRROR
 * reflects the map about its border (pixel -1 is pixel 0).
 *
 *   tex_map *b = tex_filter_blur(m, 2.0, TEX_EDGE_WRAP);
 *
 * Filters:
 *   blur      Gaussian, separable, exact sampled kernel exp(-x^2 / 2 sigma^2)
 *             over |x| <= ceil(4 sigma), normalised to sum 1 (any sigma > 0)
 *   box       mean over a (2r+1)^2 square, separable
 *   smooth    the 3x3 binomial [1 2 1]^T [1 2 1] / 16: removes one-pixel
 *             discontinuities while keeping the map's structure
 *   sharpen   unsharp mask: m + amount (m - blur_sigma(m))
 *   edges     edge enhancement: m - amount * Laplacian(m) (4-neighbour)
 *   sobel     Sobel gradient per channel, divided by 8 so that a ramp rising
 *             by s per pixel gives s: magnitude sqrt(gx^2 + gy^2) * scale, or
 *             with direction, atan2(-gy, gx) / 2 pi wrapped to [0,1)
 *             (0 = increasing to the right, 0.25 = increasing upwards)
 *   emboss    0.5 + strength * (directional Sobel derivative towards the
 *             light at angle degrees, counter-clockwise from +x)
 *   median    per-channel median of a (2r+1)^2 square
 *   noise     adds Gaussian noise of standard deviation sd; the same seed
 *             gives the same noise on any thread count
 *   normal    a normal map from a height map (dark = depression, light =
 *             elevation): n = normalise(-k dh/dx, k dh/dy, 1) with Sobel
 *             derivatives per pixel (y up), stored as n * 0.5 + 0.5 in RGB
 *   gradient  the height map's gradient (dh/du, dh/dv) in texture units
 *             (u across the width, v down the height), 2 channels: the Fu,
 *             Fv of Blinn's bump mapping
 * Colour filters leave an alpha channel (the 4th of RGBA) unchanged, except
 * the smoothing ones (blur, box, smooth, median), which treat it as data.
 * normal and gradient take the luminance (Rec. 709 weights) of RGB input.
 *
 * Every filter runs its rows in parallel (OpenMP); each output sample is
 * computed in a fixed order, so results are the same for any thread count.
 */
#ifndef TEX_FILTER_H
#define TEX_FILTER_H

#include <stdint.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

/* The blur kernel's half-width for sigma: ceil(4 sigma). */
int tex_blur_radius(double sigma);

tex_map *tex_filter_blur(const tex_map *m, double sigma, enum tex_edge e);
/* The one Gaussian blur, without tex_filter_blur's checks (sigma > 0, the
 * kernel within the map): the composition language's blur calls it too. */
tex_map *tex_filter_gaussian(const tex_map *m, double sigma, enum tex_edge e);
tex_map *tex_filter_box(const tex_map *m, int radius, enum tex_edge e);
tex_map *tex_filter_smooth(const tex_map *m, enum tex_edge e);
tex_map *tex_filter_sharpen(const tex_map *m, double sigma, double amount, enum tex_edge e);
tex_map *tex_filter_edges(const tex_map *m, double amount, enum tex_edge e);
tex_map *tex_filter_sobel(const tex_map *m, int direction, double scale, enum tex_edge e);
tex_map *tex_filter_emboss(const tex_map *m, double angle, double strength, enum tex_edge e);
tex_map *tex_filter_median(const tex_map *m, int radius, enum tex_edge e);
tex_map *tex_filter_noise(const tex_map *m, double sd, uint64_t seed);
/* The noise of rows y0.. of a map of m's width, m holding those rows (a band of a stream):
 * each sample's noise is that of its place in the whole map. */
tex_map *tex_filter_noise_rows(const tex_map *m, double sd, uint64_t seed, int y0);
tex_map *tex_filter_normal(const tex_map *m, double strength, enum tex_edge e);
tex_map *tex_filter_gradient(const tex_map *m, enum tex_edge e);
/* The gradient in the texture units of a map full_h rows high of which m holds some rows
 * (a band of a stream): v runs down full_h, not m's height. */
tex_map *tex_filter_gradient_rows(const tex_map *m, enum tex_edge e, int full_h);

/* A separable convolution with the symmetric kernel k[0..r] (k[j] weighs
 * offsets +j and -j) along x and then y; the building block of blur, box
 * and smooth.  Any r: the edge rule extends the map as far as it needs. */
tex_map *tex_filter_separable(const tex_map *m, const float *k, int r, enum tex_edge e);

/* A band of a stream: the filter's rows skip..h-1-skip of m only, the skip rows above and
 * below being their context (skip 0: the whole map).  The same bits as those rows of the
 * whole map's filter, when skip is at least the kernel's reach. */
tex_map *tex_filter_separable_rows(const tex_map *m, const float *k, int r, enum tex_edge e,
                                   int skip);
tex_map *tex_filter_blur_rows(const tex_map *m, double sigma, enum tex_edge e, int skip);
tex_map *tex_filter_box_rows(const tex_map *m, int radius, enum tex_edge e, int skip);
tex_map *tex_filter_smooth_rows(const tex_map *m, enum tex_edge e, int skip);

TEX_API_END
#endif
