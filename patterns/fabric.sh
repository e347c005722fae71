#!/bin/sh
# fabric.sh - a woven fabric, the thesis's Photo 6.1 (an imitation of cloth from a fractal
# primitive) with the threads its future work asks for (section 6.2): t_weave interlaces an
# indigo warp and a paler weft in a 2/2 twill, with yarn irregularity; a fractal (fBm)
# mottles the dye as the photo's clouds do; the weave's height map gives the bump, and a
# render drapes the cloth over a cylinder.
#   patterns/fabric.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_colour, _height, _render
recipe=fabric
. "$(dirname "$0")/recipe.sh"
# about 10 pixels a thread, so that each thread's crown and sides show
n=$((W / 10 < 8 ? 8 : W / 10))
n=$(((n + 3) / 4 * 4)) # whole repeats of the twill: the map tiles
weave="-s $size --thread-count $n --weave twill --irregularity 0.35 --warp-colours #26406e --weft-colours #8fa3c8 -S $((21 + S)) --tile"
t_weave $weave -o "$tmp/weave.exr"
t_weave $weave --map height -o "$tmp/height.exr"
t_fractal -s "$size" --octaves 6 -S $((22 + S)) --tile | t_remap --levels 0.2,0.8,0.75,1.1 -o "$tmp/mottle.exr"
t_op mul "$tmp/weave.exr" "$tmp/mottle.exr" -o "$tmp/colour.exr"
write "$tmp/colour.exr" colour
write "$tmp/height.exr" height
scene "texture cloth file \"@TMP@/colour.exr\"
texture relief file \"@TMP@/height.exr\"
camera { eye 0 1.2 -3.4 look 0 0.3 0 fov 40 }
light point { position -2 4 -3 intensity 0.9 }
image 640 400 samples 4
ambient 0.25 0.25 0.25 background 0.9 0.9 0.92
surface fabric { Ka 0.5 Kd 1 Ks 0.08 n 8
    apply cloth { mapping natural repeat 4 2 Kd = f }
    apply relief { mapping natural repeat 4 2 bump = 0.004 }
}
cylinder { base -1.5 0.3 0 top 1.5 0.3 0 radius 0.6 surface fabric }"
t_apply "$tmp/s.scene" -s "$((W * 5 / 4))x$((W * 25 / 32))" -q -o "$tmp/render.exr"
write "$tmp/render.exr" render
