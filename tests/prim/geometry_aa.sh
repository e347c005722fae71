#!/bin/bash
# geometry_aa.sh - maps of the geometric primitives by spans (box2, prim.c): the
# colour map, subsampling only the pixels an edge may cross, gives the bytes of
# subsampling every pixel (TEXTURA_AA=full), and --ids, evaluating only the
# centres box2 leaves unsure, the bytes of evaluating every centre; thin
# features, cells smaller than a pixel and tiny, odd sizes included; -j 1 = -j 2;
# a window (whose spans start elsewhere) = the same pixels cut from the whole map.
# PFM holds the floats as they are and no command line, so cmp compares pixels.
. "${TEXTURA_TOP:-.}/tests/lib.sh"
. "${TEXTURA_TOP:-.}/tests/prim/geometry_aa.lib"

cmp_aa "circle" t_circle
cmp_aa "circle thin (r 0.003), 5 x 3 cells" t_circle -r 0.003 --nu 5 --nv 3
cmp_aa "circle r 0.7 (cut by the cell)" t_circle -r 0.7
cmp_aa "ring" t_ring
cmp_aa "ring thinner than a subsample" t_ring -r 0.37 --ring-width 0.0007
cmp_aa "ring width = radius" t_ring -r 0.3 --ring-width 0.3 --nu 3
cmp_aa "ellipse" t_ellipse
cmp_aa "ellipse thin band at 30 degrees" t_ellipse --M 0.48 --m 0.1 --band-width 0.001 -a 30
cmp_aa "ellipse band = minor, 7 x 2 cells" t_ellipse --m 0.2 --band-width 0.2 -a -75 --nu 7 --nv 2
cmp_aa "flower" t_flower
cmp_aa "flower 41 petals" t_flower --petals 41 --petal-length 0.49
cmp_aa "flower 40 petals, 3 x 3" t_flower --petals 40 --nu 3 --nv 3
cmp_aa "flower 1000 petals" t_flower --petals 1000
cmp_aa "checker" t_checker
cmp_aa "checker 3 x 5 cells" t_checker --nu 3 --nv 5
cmp_aa "checker 4096 cells (smaller than a pixel)" t_checker --nu 4096 --nv 33
cmp_aa "stripe" t_stripe
cmp_aa "stripe thin, 17 degrees" t_stripe --stripe-width 0.001 --spacing 0.03 -a 17
cmp_aa "stripe no spacing" t_stripe --spacing 0 -a 90 --nu 2
cmp_aa "stripe at 0 degrees, 3 cells" t_stripe -a 0 --stripe-width 0.05 --spacing 0.0005 --nv 3
cmp_aa "cycloid" t_cycloid
cmp_aa "cycloid thin arch" t_cycloid --arch-width 0.0005 -r 60 --nu 2
cmp_aa "cycloid arch width = height" t_cycloid -r 50 --arch-width 0.15915494
cmp_aa "hypocycloid" t_hypocycloid
cmp_aa "hypocycloid thin band" t_hypocycloid -r 0.6 --band-width 0.001 --nu 2 --nv 3
