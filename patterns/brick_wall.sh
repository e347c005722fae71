#!/bin/sh
# brick_wall.sh - the brick wall of the thesis's Photo 4.1: a random colour per brick
# (t_brick --cells through the brick palette) and sunken mortar (a bump from the
# brick/mortar subregions), rendered under a grazing light.
#   patterns/brick_wall.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_colour, _height, _render
recipe=brick_wall
. "$(dirname "$0")/recipe.sh"
# fired clay, from underburnt to overburnt: each brick one colour of it
printf 'space oklab\n0 #6e2a1a\n0.35 #9a3b22\n0.7 #b5573a\n1 #c98a5a\nindex 1 #cfc6b8\n' \
    >"$tmp/clay.pal"
t_brick -s "$size" --nu 4 --nv 8 --cells --palette "$tmp/clay.pal" -S $((7 + S)) --tile -o "$tmp/colour.exr"
t_brick -s "$size" --nu 4 --nv 8 --tile --palette greys -o "$tmp/h.exr"
t_filter blur --sigma 1.2 --edge wrap "$tmp/h.exr" -o "$tmp/height.exr"
write "$tmp/colour.exr" colour
write "$tmp/height.exr" height
scene "image 640 400
samples 4
ambient 0.25 0.25 0.25
camera { eye 0 1 -3 look 0 1 0 fov 50 }
light distant { direction -3 1 -1.2 intensity 1 }
texture colour file \"@TMP@/colour.exr\"
texture height file \"@TMP@/height.exr\"
surface wall { Ka 0.5 Kd 1
    apply colour { mapping natural repeat 2 1 Kd = f }
    apply height { mapping natural repeat 2 1 bump = 0.02 } }
box { min -2 0 0 max 2 2 0.3 surface wall }"
t_apply "$tmp/s.scene" -s "$((W * 5 / 4))x$((W * 25 / 32))" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
