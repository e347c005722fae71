#!/bin/sh
# rust_steel.sh - rust on steel: a mask from ridged multifractal noise blends a rust
# surface into stainless steel (Cook-Torrance, the database's optical constants), and a
# roughness map widens the steel's highlights where rust is near (m = 0.08 + 0.3 f).
#   patterns/rust_steel.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_mask, PREFIX_render
recipe=rust_steel
. "$(dirname "$0")/recipe.sh"
t_fractal -m ridged -s "$size" -f 3 -n 7 -S $((13 + S)) --tile -o "$tmp/r.exr"
t_remap --levels 0.6,0.9,0,1 "$tmp/r.exr" -o "$tmp/mask.exr"
write "$tmp/mask.exr" mask
scene "image 480 360
samples 4
ambient 0.25 0.25 0.25
background 0.1 0.1 0.12
camera { eye 0 1.6 -3.6 look 0 0.6 0 fov 45 }
light point { position -3 5 -4 intensity 1.2 }
light distant { direction 2 1 -1 intensity 0.3 }
texture mask file \"@TMP@/mask.exr\"
surface rust { Ka 0.3 Kd 0.42 0.17 0.06 Ks 0.05 n 5 }
surface steel { model cook-torrance material stainless Ka 0.2 Kd 0.2 0.2 0.22 specular 0.7
    facets beckmann 0.08 Kr 0.3 blend rust
    apply mask { mapping cylinder repeat 2 1 blend = f m = 0.08 + 0.3 * f } }
cylinder { base 0 0 0 top 0 1.4 0 radius 0.8 surface steel }
plane { surface rust }"
TEXTURA_MATERIALS=$here/materials.txt t_apply "$tmp/s.scene" -s "$((W * 15 / 16))x$((W * 45 / 64))" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
