#!/bin/sh
# composed_cracks.sh - cells with cracks as a composed primitive (patterns/primitives.tp):
# a random grey per Voronoi cell times a smooth step of the border distance F2 - F1,
# whose width turbulence varies, like dried mud or crazed glaze.
#   patterns/composed_cracks.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_cracks, PREFIX_mud
recipe=composed_cracks
. "$(dirname "$0")/recipe.sh"
t_expr --defs "$here/primitives.tp" cracked --cells 60 -S $((4 + S)) -s "$size" -o "$tmp/c.exr"
write "$tmp/c.exr" cracks
t_palette granite "$tmp/c.exr" -o "$tmp/mud.exr"
write "$tmp/mud.exr" mud
