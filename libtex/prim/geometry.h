/* geometry.h - the geometric primitives of the thesis (5.2.1.1, Appendix A)
 *
 * Each primitive splits texture space into numbered subregions and is a
 * REGIONS primitive (prim.h): eval2 writes the region id 1..nregions of each
 * point as a float.  Sampled with ids off, the field carries one colour per
 * region (the --color1.. rows, or a palette) and the sampler antialiases the
 * edges by coverage; with --ids the map holds the exact id of each pixel
 * centre and textura:subregions = nregions.  Each primitive's box2 proves
 * boxes of points one region from its geometry (geometry.c: the rule), so
 * that the sampler subsamples only the pixels an edge may cross, and with
 * --ids evaluates only the centres near one.
 *
 * General parameters (Appendix A.1-A.2), on every primitive:
 *   nu, nv   repetitions: the pattern fills one cell of a nu x nv grid over
 *            the unit square, cell coordinates x = frac(u nu), y = frac(v nv)
 *   centre   (0.5,0.5) of the cell, y up, for the figures; the lower-left
 *            corner for the cycloid (the thesis's polar/corner convention)
 *   colours  --color1, --color2 [, --color3]: region k's colour
 *
 * Regions, numbered as the thesis does (left to right, top to bottom: the
 * ground around a figure comes first, then inward):
 *   circle       1 outside, 2 inside the circle of radius r
 *   ring         1 outside, 2 the ring (r-d < dist <= r), 3 inside
 *   ellipse      1 outside, 2 the band between the ellipses (M,m) and
 *                (M-d,m-d), 3 inside
 *   flower       1 ground, 2 the rose r = d sin(n theta) (n petals for odd
 *                n, 2n for even n)
 *   checker      1 the top-left square and its like, 2 the others
 *   stripe       1 between the stripes, 2 the stripes
 *   cycloid      1 above the outer arch, 2 between the arches, 3 inside
 *   hypocycloid  1 outside, 2 between the astroids, 3 inside
 *   four_rings   1 ground, 2 the four rings
 *   polygon/star 1 outside, 2 inside
 *   grid         1 the cells, 2 the lines
 *   brick        1 the bricks, 2 the mortar
 *   dots         1 ground, 2 the dots
 *
 * Solid variants (eval3, cells nu x nv x nw): circle (a ball), ring
 * (concentric spheres) and checker.
 */
#ifndef TEX_GEOMETRY_H
#define TEX_GEOMETRY_H

#include "../base/api.h"
#include "prim.h"

TEX_API_BEGIN

/* The region id of an initialised geometric field at one point (u,v). */
int tex_geometry_region(const struct tex_field *f, double u, double v);

TEX_API_END
#endif
