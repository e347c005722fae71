#!/bin/sh
# granite.sh - granite: crystals of three minerals (a random value per Voronoi cell of
# t_bubble, through the granite palette) speckled by fine noise.
#   patterns/granite.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_colour
recipe=granite
. "$(dirname "$0")/recipe.sh"
t_bubble -s "$size" -c 3000 --value cell --distribution poisson -S $((11 + S)) --tile -o "$tmp/cells.exr"
t_noise -s "$size" -f 96 -S $((12 + S)) --tile -o "$tmp/fine.exr"
t_op mul "$tmp/fine.exr" 0.35 | t_op add - "$tmp/cells.exr" | t_op mul - 0.85 -o "$tmp/v.exr"
t_palette granite "$tmp/v.exr" -o "$tmp/colour.exr"
write "$tmp/colour.exr" colour
