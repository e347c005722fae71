#!/bin/bash
# geometry_aa2.sh - the rest of geometry_aa.sh's primitives (the two halves fit the
# sanitizer build's time budget); the checks are geometry_aa.lib's.
. "${TEXTURA_TOP:-.}/tests/lib.sh"
. "${TEXTURA_TOP:-.}/tests/prim/geometry_aa.lib"

cmp_aa "hypocycloid band = radius" t_hypocycloid -r 0.3 --band-width 0.3
cmp_aa "four_rings" t_four_rings
cmp_aa "four_rings interlaced, thin" t_four_rings -r 0.4 --ring-width 0.0008
cmp_aa "four_rings width = radius" t_four_rings -r 0.3 --ring-width 0.3 --nu 3
cmp_aa "polygon" t_polygon
cmp_aa "polygon 1000 sides, 13 degrees" t_polygon --sides 1000 -a 13 -r 0.5
cmp_aa "polygon triangle, 6 x 4" t_polygon --sides 3 --nu 6 --nv 4
cmp_aa "star" t_star
cmp_aa "star 97 points" t_star --sides 97 --inner-radius 0.05
cmp_aa "star 2 points, inner 0" t_star --sides 2 --inner-radius 0 -a 7
cmp_aa "star inner 1" t_star --sides 7 --inner-radius 1 --nu 2
cmp_aa "star radius 0" t_star -r 0
cmp_aa "grid" t_grid
cmp_aa "grid thin lines, 13 x 5" t_grid --line-width 0.002 --nu 13 --nv 5
cmp_aa "grid lines fill the cell" t_grid --line-width 1 --nu 3
cmp_aa "brick" t_brick
cmp_aa "brick thin mortar, 9 x 7" t_brick --mortar-width 0.003 --nu 9 --nv 7
cmp_aa "brick no mortar" t_brick --mortar-width 0
cmp_aa "brick --cells" t_brick --cells --nu 5 --nv 3
cmp_aa "brick --cells, no mortar" t_brick --cells --mortar-width 0 --nu 6 --nv 6
cmp_aa "dots" t_dots
cmp_aa "dots tiny" t_dots -r 0.002 --nu 9 --nv 5
cmp_aa "dots touching" t_dots -r 0.354 --nu 3 --nv 2
pal=$(ls "$TEXTURA_TOP/palettes" | head -1)
cmp_one "circle with a palette" t_circle --palette "$TEXTURA_TOP/palettes/$pal"
