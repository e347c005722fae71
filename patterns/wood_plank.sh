#!/bin/sh
# wood_plank.sh - a varnished wood plank, modelled as the thesis's section 4.5 and Figure 4.7
# do, from three optical characters: the colour, brown concentric ellipses with perturbed
# edges (t_wood, the log cut at a slant) crossed by dark, nearly parallel lines; the
# brightness, uniform over a varnished surface, so its map is constant and the varnish is a
# surface of high specularity; the roughness, randomly placed, nearly parallel line segments
# (t_segments) whose grooves are slight depressions: a bump.  A render shows the plank.
#   patterns/wood_plank.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_colour, _brightness, _roughness,
#                                                  _render (.png and .exr)
recipe=wood_plank
. "$(dirname "$0")/recipe.sh"
# Lines and grooves at least 3 pixels wide, whatever the size: a point-sampled line thinner
# than a pixel breaks into dashes.
w=$(awk -v s="$W" 'BEGIN { w = 3 / s; printf "%.6f", w < 0.006 ? 0.006 : w }')
t_wood -s "$size" --tilt 75 --axis-offset 0.25 --rings 7 --turbulence 0.1 --grain 0.25 -S $((4 + S)) -o "$tmp/rings.exr"
t_segments -s "$size" --angle 90 --angle-spread 1.5 --segments 60 --length 0.35 --width "$w" -S $((6 + S)) --tile |
    t_op mul - 0.55 | t_op sub 1 - -o "$tmp/lines.exr"
t_palette wood "$tmp/rings.exr" | t_op mul - "$tmp/lines.exr" -o "$tmp/colour.exr"
t_op mul "$tmp/rings.exr" 0 | t_op add - 0.8 -o "$tmp/brightness.exr"
t_segments -s "$size" --angle 90 --angle-spread 3 --segments 300 --length 0.15 --width "$w" -S $((5 + S)) --tile -o "$tmp/roughness.exr"
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
texture rough file \"@TMP@/roughness.exr\"
surface varnished { Ka 0.4 Kd 1 Ks 0.6 n 90 Kr 0.08
    apply colour { mapping planar Kd = f }
    apply rough { mapping planar bump = -0.002 }
}
box { min -1.2 -0.1 -2 max 1.2 0 2 surface varnished }"
t_apply "$tmp/s.scene" -s "$((W * 5 / 4))x$((W * 5 / 8))" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
