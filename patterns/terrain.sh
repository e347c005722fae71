#!/bin/sh
# terrain.sh - a terrain heightmap (Musgrave's hybrid multifractal: smooth valleys, rough
# peaks) as a 32-bit EXR for a modelling tool, and coloured by height with the earth
# palette (sea, beach, grass, rock, snow).
#   patterns/terrain.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_height, PREFIX_colour
recipe=terrain
. "$(dirname "$0")/recipe.sh"
t_fractal -m hybrid --mf-offset 0.7 -s "$size" -f 3 -n 9 -S $((17 + S)) -o "$tmp/height.exr"
write "$tmp/height.exr" height
t_palette earth "$tmp/height.exr" -o "$tmp/colour.exr"
write "$tmp/colour.exr" colour
