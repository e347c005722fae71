#!/bin/sh
# composed_marble.sh - marble as a composed primitive (patterns/primitives.tp): the
# expression 0.5 + 0.5 sin(2 pi veins u + strength turbulence) is a primitive of its own,
# written once and used both as a flat map (t_expr) and as a solid texture in a scene.
#   patterns/composed_marble.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_map, PREFIX_render
recipe=composed_marble
. "$(dirname "$0")/recipe.sh"
t_expr --defs "$here/primitives.tp" marble --veins 3 --strength 6 -S $((5 + S)) -s "$size" -o "$tmp/m.exr"
t_palette marble "$tmp/m.exr" -o "$tmp/map.exr"
write "$tmp/map.exr" map
scene "image 320 320
samples 2
ambient 0.3 0.3 0.3
background 0.12 0.12 0.14
camera { eye 0 1.2 -3.4 look 0 0.8 0 fov 40 }
light point { position -3 5 -4 intensity 0.9 }
primitives \"$here/primitives.tp\"
texture veins marble { solid veins 2 seed 5 }
surface stone { Ka 0.35 Kd 0.9 Ks 0.5 n 60
    apply veins { mapping solid Kd = palette(marble, f) } }
sphere { centre 0 0.8 0 radius 0.8 surface stone }"
t_apply "$tmp/s.scene" -s "${W}x$H" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
