#!/bin/sh
# tileable.sh - maps that tile seamlessly for game engines: wood (anisotropic spectral
# synthesis along the grain through the wood palette), stone (cells of t_bubble with
# cracks, F2 - F1), fabric (the plain weave of fabric.sh) and ground (fBm through the
# earth palette's land colours).  Every generator runs with --tile, and filters wrap.
#   patterns/tileable.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_wood, _stone, _fabric, _ground
recipe=tileable
. "$(dirname "$0")/recipe.sh"
t_spectral -s "$size" --hurst 0.9 --anisotropy 90,20 -S $((31 + S)) --tile -o "$tmp/w.exr"
t_palette wood "$tmp/w.exr" -o "$tmp/wood.exr"
write "$tmp/wood.exr" wood
t_bubble -s "$size" -c 60 --value f2-f1 --distribution poisson -S $((32 + S)) --tile -o "$tmp/cr.exr"
t_remap --levels 0,0.05,0.25,1 "$tmp/cr.exr" -o "$tmp/cracks.exr"
t_fractal -s "$size" -f 8 -n 6 -S $((33 + S)) --tile | t_op mul - "$tmp/cracks.exr" -o "$tmp/s.exr"
t_palette greys "$tmp/s.exr" -o "$tmp/stone.exr"
write "$tmp/stone.exr" stone
"$here/fabric.sh" -o "$tmp/f" -s "$size" >/dev/null
t_convert "$tmp/f_colour.exr" -o "$tmp/fabric.exr"
write "$tmp/fabric.exr" fabric
t_fractal -s "$size" -f 6 -n 8 -S $((34 + S)) --tile | t_remap --levels 0,1,0.45,1 -o "$tmp/g.exr"
t_palette earth --range 0,1 "$tmp/g.exr" -o "$tmp/ground.exr"
write "$tmp/ground.exr" ground
