#!/bin/sh
# marble_vase.sh - a marble vase carved from a solid texture (thesis 5.2.4.1): the veins
# are Perlin's marble, sin(6 x + 12 turbulence) through the marble palette, evaluated
# at each hit point, so they run through the vase's body and neck alike.
#   patterns/marble_vase.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_render, PREFIX_slice
recipe=marble_vase
. "$(dirname "$0")/recipe.sh"
scene "image 480 480
samples 4
ambient 0.3 0.3 0.3
background 0.12 0.12 0.14
camera { eye 0 1.6 -4.2 look 0 1 0 fov 45 }
light point { position -3 5 -4 intensity 0.9 }
light distant { direction 2 1 -1 intensity 0.3 }
texture veins turbulence { solid frequency 2 octaves 6 seed 3 }
surface marble { Ka 0.35 Kd 0.9 Ks 0.6 n 80 Kr 0.06
    apply veins { mapping solid Kd = palette(marble, 0.5 + 0.5 * sin(6 * ox + 12 * f)) } }
surface plinth { Ka 0.3 Kd 0.25 0.22 0.2 }
union {
    sphere { centre 0 0.9 0 radius 0.75 }
    cylinder { base 0 1.3 0 top 0 2 0 radius 0.28 }
    torus { centre 0 2 0 major 0.28 minor 0.06 }
    surface marble
}
box { min -2 -0.2 -2 max 2 0.15 2 surface plinth }"
t_apply "$tmp/s.scene" -s "${W}x$H" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
# the same field as a flat map: a slice through the block
t_turbulence -s "$size" -f 2 -n 6 -S $((3 + S)) --slice 0.5 -o "$tmp/t.exr"
t_palette marble "$tmp/t.exr" -o "$tmp/slice.exr"
write "$tmp/slice.exr" slice
