/* cell.h - the cell of a solid texture's lattice that a point lies in, robust on the
 * cells' faces (libtex internal)
 *
 * A solid texture's lattice has faces at whole numbers of its cells, and the surfaces
 * users make lie on them: the floor y = 0 under a world mapping, a box's faces under the
 * solid mapping (0 and 1 across its box), a cylinder's caps.  A hit on such a face is the
 * face's coordinate give or take a rounding of the ray's arithmetic, and floor alone puts
 * neighbouring hits in either cell at random: salt-and-pepper pixels over the whole
 * surface.  As POV-Ray's checker pattern does (floor(x + EPSILON), EPSILON 1e-10, in
 * source/core/material/pattern.cpp), a point less than TEX_CELL_EPS below a face belongs
 * to the cell above it, so that a surface on a face lies in one cell.  Away from the faces
 * the cell is floor's, bit for bit.
 *
 *   tex_cell_floor(x)   the cell of x, a whole number: floor(x + TEX_CELL_EPS)
 *   tex_cell_frac(x)    x's place in it, x - tex_cell_floor(x), in [-TEX_CELL_EPS, 1)
 */
#ifndef TEX_CELL_H
#define TEX_CELL_H

#include <math.h>

/* In cells: above the hits' rounding (about 1e-15 of the coordinates) where a lattice of
 * 4096 cells a side spans a few units, below any feature a map resolves. */
#define TEX_CELL_EPS 1e-10

static inline double tex_cell_floor(double x)
{
    return floor(x + TEX_CELL_EPS);
}

static inline double tex_cell_frac(double x)
{
    return x - tex_cell_floor(x);
}

#endif
