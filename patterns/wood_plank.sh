#!/bin/sh
# wood_plank.sh - a varnished wood plank, as the thesis's Figure 4.7 builds it: one map of
# growth rings (t_wood, flat-sawn) gives the colour through the wood palette, the
# brightness (late wood darker) and the roughness (late wood rougher, the varnish
# smoothing all of it); a render shows the plank varnished (Ks and Kr from the maps).
#   patterns/wood_plank.sh [-o PREFIX] [-s N]   -> PREFIX_colour, _brightness, _roughness,
#                                                  _render (.png and .exr)
recipe=wood_plank
. "$(dirname "$0")/recipe.sh"
t_wood -s "$size" --tilt 84 --axis-offset 0.42 --rings 9 --turbulence 0.05 --grain 0.3 -S 4 -o "$tmp/rings.exr"
t_palette wood "$tmp/rings.exr" -o "$tmp/colour.exr"
t_remap --levels 0,1,1,0.55 "$tmp/rings.exr" -o "$tmp/brightness.exr"
t_remap --levels 0,1,0.15,0.45 "$tmp/rings.exr" -o "$tmp/roughness.exr"
write "$tmp/colour.exr" colour
write "$tmp/brightness.exr" brightness
write "$tmp/roughness.exr" roughness
scene "image 640 360
samples 4
ambient 0.3 0.3 0.3
background 0.15 0.15 0.17
camera { eye 0 2.2 -3.2 look 0 0 0.3 fov 45 }
light point { position -2 4 -3 intensity 0.9 }
light distant { direction 1 2 -1 intensity 0.3 }
texture colour file \"@TMP@/colour.exr\"
texture bright file \"@TMP@/brightness.exr\"
texture rough file \"@TMP@/roughness.exr\"
surface varnished { Ka 0.4 Kd 1 Ks 0.6 n 90 Kr 0.08
    apply colour { mapping planar Kd = f }
    apply bright { mapping planar Kd = p * f }
    apply rough { mapping planar n = 20 + 200 * (1 - f) Ks = 0.9 - f } }
box { min -1.2 -0.1 -2 max 1.2 0 2 surface varnished }"
t_apply "$tmp/s.scene" -s "$((size * 5 / 4))x$((size * 5 / 8))" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
