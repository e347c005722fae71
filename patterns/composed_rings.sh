#!/bin/sh
# composed_rings.sh - wood-like growth rings as a composed primitive (patterns/primitives.tp):
# the distance from an axis, wobbled by noise, through a smooth step for the late wood;
# the axis runs along w, so as a solid texture the rings are a log's.
#   patterns/composed_rings.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_rings, PREFIX_plank
recipe=composed_rings
. "$(dirname "$0")/recipe.sh"
t_expr --defs "$here/primitives.tp" rings -S $((2 + S)) -s "$size" -o "$tmp/r.exr"
t_palette wood --range 0,1 "$tmp/r.exr" -o "$tmp/rings.exr"
write "$tmp/rings.exr" rings
# a plank: the same rings cut far from the axis: u and v swapped and squeezed
# (coordinates given to a call warp its domain)
t_expr --defs "$here/primitives.tp" 'rings(0.5 + 0.4*v, 0.9 + 0.05*u, rings = 40, wobble = 0.5)' \
    -S $((2 + S)) -s "$size" -o "$tmp/p.exr"
t_palette wood --range 0,1 "$tmp/p.exr" -o "$tmp/plank.exr"
write "$tmp/plank.exr" plank
