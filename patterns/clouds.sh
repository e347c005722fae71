#!/bin/sh
# clouds.sh - clouds in a sky: fBm through the clouds palette over the sky palette's
# blue, and the same as a lat-long environment for t_apply (environment FILE).
#   patterns/clouds.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_clouds, PREFIX_sky (2:1 lat-long)
recipe=clouds
. "$(dirname "$0")/recipe.sh"
t_fractal -s "$size" -f 4 -n 8 -S $((8 + S)) --tile -o "$tmp/fbm.exr"
t_palette clouds "$tmp/fbm.exr" -o "$tmp/clouds.exr"
write "$tmp/clouds.exr" clouds
t_fractal -s "$((2 * W))x$H" -f 6 -n 8 -S $((9 + S)) -o "$tmp/fbm2.exr"
t_palette sky "$tmp/fbm2.exr" -o "$tmp/sky.exr"
write "$tmp/sky.exr" sky
