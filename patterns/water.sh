#!/bin/sh
# water.sh - water ripples: a tangent-space normal map from the analytic gradient of
# noise (t_d_noise --normal, quintic fade: no creases), applied as `normal = f` to a
# pool reflecting a sky of clouds.
#   patterns/water.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_normal, PREFIX_render
recipe=water
. "$(dirname "$0")/recipe.sh"
t_d_noise --normal --strength 0.6 --fade quintic -f 12 -s "$size" -S $((3 + S)) --tile -o "$tmp/normal.exr"
write "$tmp/normal.exr" normal
t_fractal -s 512x256 -f 6 -n 7 -S $((9 + S)) | t_palette sky -o "$tmp/sky.exr"
scene "image 640 360
samples 4
ambient 0.1 0.12 0.15
camera { eye 0 1.2 -4 look 0 0 2 fov 55 }
light distant { direction -1 1.5 2 intensity 0.8 }
environment \"@TMP@/sky.exr\"
texture ripples file \"@TMP@/normal.exr\"
surface water { Ka 0.2 Kd 0.02 0.08 0.1 Ks 0.8 n 200 Kr 0.7
    apply ripples { mapping planar scale 0.25 normal = f } }
plane { surface water }"
t_apply "$tmp/s.scene" -s "$((W * 5 / 4))x$((W * 45 / 64))" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
