#!/bin/sh
# orange_peel.sh - the thesis's orange peel (2.3.3): midpoint displacement with a Hurst
# exponent per level, h = 10 for the first levels (almost no large relief), 0 in the
# middle and -10 then 10 at the finest (the pores), used as a bump on an orange.
#   patterns/orange_peel.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_height, PREFIX_render
recipe=orange_peel
. "$(dirname "$0")/recipe.sh"
t_fractal -m midpoint --hurst 10,0,0,0,0,0,-10,10 -s "$size" -S $((5 + S)) --tile -o "$tmp/h.exr"
t_remap --levels 0.3,0.7,0,1 "$tmp/h.exr" -o "$tmp/height.exr"
write "$tmp/height.exr" height
scene "image 400 400
samples 4
ambient 0.3 0.3 0.3
background 0.1 0.1 0.12
camera { eye 0 0.4 -3 look 0 0 0 fov 40 }
light point { position -3 4 -4 intensity 1 }
texture peel file \"@TMP@/height.exr\"
surface orange { Ka 0.3 Kd 0.95 0.45 0.05 Ks 0.35 n 40
    apply peel { mapping sphere repeat 4 2 bump = 0.015 } }
sphere { radius 1 surface orange }"
t_apply "$tmp/s.scene" -s "${W}x$H" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
