#!/bin/sh
# fabric.sh - a woven fabric as in the thesis's Photo 6.1: anisotropic spectral synthesis
# makes the threads (structures stretched along u for the warp, along v for the weft),
# and a checker of weave cells chooses warp or weft in each (a plain weave, t_cascade).
#   patterns/fabric.sh [-o PREFIX] [-s N]   -> PREFIX_colour
recipe=fabric
. "$(dirname "$0")/recipe.sh"
t_spectral -s "$size" --hurst 0.6 --anisotropy 0,12 -S 21 --tile -o "$tmp/warp.exr"
t_spectral -s "$size" --hurst 0.6 --anisotropy 90,12 -S 22 --tile -o "$tmp/weft.exr"
t_checker -s "$size" --nu 32 --nv 32 --ids --tile -o "$tmp/weave.exr"
t_cascade "$tmp/weave.exr" 1="$tmp/warp.exr" 2="$tmp/weft.exr" -o "$tmp/threads.exr"
printf 'space oklab\n0 #1d2f5a\n1 #8da4d4\n' >"$tmp/indigo.pal"
t_palette "$tmp/indigo.pal" "$tmp/threads.exr" -o "$tmp/colour.exr"
write "$tmp/colour.exr" colour
