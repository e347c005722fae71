/* cellular.h - point sets and nearest-point queries (bubbles, Voronoi cells)
 *
 * The thesis's t.bubble (5.2.2.5) shades every point of texture space by
 * its distance to the nearest of N random points.  This module owns the
 * point sets and answers, for any query point q, the distances F1 and F2
 * to the nearest and second-nearest point and the index of the nearest.
 *
 * Point sets (tex_points): dim 2 or 3, coordinates x[i*dim + j], and
 * optionally per-point bubble radii axes[i*dim + j] (NULL: all 1).
 *
 *   tex_points ps;
 *   tex_points_random(&ps, 2, 1000, TEX_POINTS_POISSON, 0, seed, tile);
 *   tex_points_vary(&ps, 0.5, 0.3, seed);       // random sizes, ellipses
 *   struct tex_cellular_opts o = {TEX_METRIC_EUCLID, 2, tile, TEX_SEARCH_AUTO, 0};
 *   tex_cellular *c = tex_cellular_new(&ps, &o);
 *   tex_cellular_query(c, n, q, f1, f2, id);    // q: n*dim doubles
 *   tex_cellular_free(c); tex_points_free(&ps);
 *
 * Distance.  From q to point i (shifted by a whole period s in each axis
 * when tiling) the distance is the metric's norm of the displacement
 * divided axis by axis by the point's radii:
 *     d_i(q) = || (q - (p_i + s)) / a_i ||
 * with ||.|| Euclidean (L2), Manhattan (L1), Chebyshev (L-infinity) or
 * Minkowski (Lp, p >= 1).  Equal radii make bubbles of different sizes
 * (a multiplicatively weighted Voronoi diagram); distinct radii per axis
 * make ellipses (ellipsoids in 3D), as the thesis describes.  With tile
 * the point set repeats with period 1 in every axis (queries are wrapped
 * into [0,1)), so the field is seamless.
 *
 * Search.  Every method returns the same F1 and F2, bit for bit, as the
 * brute-force reference, and the same nearest index (ties go to the lower
 * index):
 *   TEX_SEARCH_BRUTE   every point (and its 3^dim periodic images)
 *   TEX_SEARCH_GRID    a uniform grid of buckets searched ring by ring
 *                      until no unvisited bucket can hold a closer point;
 *                      2D Euclidean without radii: per-bucket candidate
 *                      lists on a finer grid, queries of one bucket (a row
 *                      of pixels) 16 at a time in vector lanes;
 *                      fastest for even sets (uniform, Poisson-disk)
 *   TEX_SEARCH_KDTREE  FLANN's exact single kd-tree (FLANN_INDEX_KDTREE_SINGLE,
 *                      unlimited checks, eps 0) on Euclidean distance; for
 *                      other metrics, radii or periodic images it fetches
 *                      k Euclidean neighbours and grows k until a norm
 *                      inequality proves no other point can be closer;
 *                      for arbitrary (clustered) sets.  In 2D (up to
 *                      2,000,000 points) FLANN's searches first fill an
 *                      adaptive tree of boxes over the unit square, each
 *                      with the complete list of points that can be one of
 *                      the two nearest inside it; queries in the square
 *                      search that list (set-up: a few us per point;
 *                      TEXTURA_BUBBLE_NO_TREE in the environment skips it)
 *   TEX_SEARCH_AUTO    the grid, unless the buckets are badly unbalanced
 * FLANN's tree runs Euclidean only (base/kdtree.h; its C API kept the
 * distance type in a process-wide variable, so two fields with different
 * metrics could not have shared a process); the bound keeps the other
 * metrics exact.  Queries are read-only and safe from many threads.
 *
 * Limits: 1..TEX_POINTS_MAX points.  Errors are reported through error.h.
 */
#ifndef TEX_CELLULAR_H
#define TEX_CELLULAR_H

#include "../base/api.h"

#include <stdint.h>

TEX_API_BEGIN

#define TEX_POINTS_MAX 10000000

enum tex_metric { TEX_METRIC_EUCLID, TEX_METRIC_MANHATTAN, TEX_METRIC_CHEBYSHEV,
                  TEX_METRIC_MINKOWSKI };
enum tex_pointdist { TEX_POINTS_UNIFORM, TEX_POINTS_POISSON, TEX_POINTS_CLUSTER };
enum tex_search { TEX_SEARCH_AUTO, TEX_SEARCH_GRID, TEX_SEARCH_KDTREE, TEX_SEARCH_BRUTE };

typedef struct tex_points {
    int dim;      /* 2 or 3 */
    long n;
    double *x;    /* n*dim coordinates */
    double *axes; /* n*dim bubble radii (> 0), or NULL for all 1 */
} tex_points;

/* n random points in [0,1)^dim from seed:
 *   UNIFORM  independent uniform points;
 *   POISSON  Poisson-disk (blue noise) by dart throwing: no two points closer
 *            than r, with r chosen so that the discs cover 40% of the square
 *            (25% of the cube in 3D), below the saturation of dart throwing;
 *            distances are periodic when tile is set;
 *   CLUSTER  `clusters` parents (0: about sqrt(n)) uniform, each point a
 *            Gaussian offset (sigma = 0.25 / clusters^(1/dim)) from a random
 *            parent, wrapped into [0,1).
 * Returns -1 on a bad n or when memory runs out. */
int tex_points_random(tex_points *ps, int dim, long n, enum tex_pointdist dist, int clusters,
                      uint64_t seed, int tile);
/* Read a points file (textura-points(5)): one point a line, "x y [w]" in 2D
 * or "x y z [w]" in 3D, blank lines and '#' comments ignored; w > 0 is the
 * bubble's radius (default 1).  Errors name path:line. */
int tex_points_read(tex_points *ps, const char *path, int dim);
/* Random bubble radii: each point's radius is multiplied by
 * 1 + size*(2u-1) and each axis of it by 1 + shape*(2u'-1) (u, u' uniform
 * in [0,1) from seed); size, shape in [0, 0.95]. */
int tex_points_vary(tex_points *ps, double size, double shape, uint64_t seed);
/* Wrap every coordinate into [0,1). */
void tex_points_wrap(tex_points *ps);
void tex_points_free(tex_points *ps);

struct tex_cellular_opts {
    enum tex_metric metric;
    double p;      /* Minkowski order, >= 1 */
    int tile;      /* periodic with period 1 */
    enum tex_search search;
    long queries;  /* queries expected (a map's pixels), 0 if unknown: sizes the tables */
};

typedef struct tex_cellular tex_cellular;

/* Build the search structure (the points are copied). NULL on failure. */
tex_cellular *tex_cellular_new(const tex_points *ps, const struct tex_cellular_opts *o);
void tex_cellular_free(tex_cellular *c);
/* The method chosen (never AUTO). */
enum tex_search tex_cellular_search(const tex_cellular *c);
/* For n query points q (n*dim doubles): f1, f2 the distances to the nearest
 * and second-nearest point (f2 = infinity with a single point and no tile),
 * id the index of the nearest; f2 and id may be NULL.  Thread-safe. */
void tex_cellular_query(const tex_cellular *c, int n, const double *q, double *f1, double *f2,
                        long *id);
/* Parse a metric: euclid, manhattan, chebyshev or minkowski:P (P in 1..TEX_METRIC_P_MAX). */
#define TEX_METRIC_P_MAX 64
int tex_metric_parse(const char *text, enum tex_metric *m, double *p);

TEX_API_END
#endif
