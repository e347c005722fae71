#!/bin/bash
# geometry_aa.sh - maps of the geometric primitives by spans (box2, prim.c): the
# colour map, subsampling only the pixels an edge may cross, gives the bytes of
# subsampling every pixel (TEXTURA_AA=full), and --ids, evaluating only the
# centres box2 leaves unsure, the bytes of evaluating every centre; thin
# features, cells smaller than a pixel and tiny, odd sizes included; -j 1 = -j 2;
# a window (whose spans start elsewhere) = the same pixels cut from the whole map.
# PFM holds the floats as they are and no command line, so cmp compares pixels.
. "${TEXTURA_TOP:-.}/tests/lib.sh"

# cmp_one NAME TOOL ARGS...: at a tiny, an odd oblong and an odd square size, sparse ==
# full, and -j 1 == -j 2;
# at 211, the window 37,20,113,70 == those pixels of the whole map.
cmp_one() {
    local name=$1 bad=""
    shift
    for s in 7 129x70 211; do
        "$@" -s $s -j 2 -o "$T/sparse.pfm" 2>"$T/err" || { bad="$bad -s $s failed: $(head -c 200 "$T/err")"; continue; }
        TEXTURA_AA=full "$@" -s $s -j 2 -o "$T/full.pfm" || { bad="$bad -s $s (full) failed"; continue; }
        "$@" -s $s -j 1 -o "$T/one.pfm" || { bad="$bad -s $s -j 1 failed"; continue; }
        cmp -s "$T/sparse.pfm" "$T/full.pfm" || bad="$bad -s $s: differs from TEXTURA_AA=full;"
        cmp -s "$T/sparse.pfm" "$T/one.pfm" || bad="$bad -s $s: -j 2 differs from -j 1;"
        [ $s = 211 ] || continue
        "$@" -s $s -j 2 --window 37,20,113,70 -o "$T/win.pfm" &&
            t_xform --clip 37,20,150,90 "$T/sparse.pfm" -o "$T/cut.pfm" ||
            { bad="$bad -s $s --window failed"; continue; }
        cmp -s "$T/win.pfm" "$T/cut.pfm" || bad="$bad -s $s: the window differs from the whole map;"
    done
    if [ -z "$bad" ]; then
        ok "$name: same bytes as every point evaluated, -j 1 = -j 2, a window = the whole's"
    else notok "$name" "$bad"; fi
}

# cmp_aa NAME TOOL ARGS...: cmp_one for the colour map and for --ids.
cmp_aa() {
    local name=$1
    shift
    cmp_one "$name" "$@"
    cmp_one "$name --ids" "$@" --ids
}

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
