#!/usr/bin/env bash
# t_weave: plain, twill and satin weaves, thread colours, irregularity, seams and bad values.
. "$(dirname "$0")/../lib.sh"

# warp MAP: the fraction of the map where the warp (red) lies on top
warp() { t_op -t 0.01 threshold "$1" | info_json - stats 0 mean; }
solid="--thread-width 1 --irregularity 0 --warp-colours #ff0000 --weft-colours #0000ff"
for w in "plain:0.5" "twill:0.5" "twill --float 3:0.75" "twill --shafts 6 --float 1:0.1666667" \
    "satin:0.8" "satin --shafts 8:0.875"; do
    args=${w%%:*} want=${w#*:}
    t_weave -s 480 --thread-count 24 $solid --weave $args -o "$T/w.exr"
    got=$(warp "$T/w.exr")
    approx "$got" "$want" 0.01 && ok "$args: the warp on top of $want of the cells" ||
        notok "$args: the warp on top of $want of the cells" "$got"
done
# The weave's structure: a plain weave is a checker of cells; a twill's ribs run diagonally,
# so shifting it one cell right and one up leaves it as it was.
t_weave -s 240 --thread-count 12 $solid --weave twill -o "$T/tw.exr"
t_xform --shift 20,-20 --wrap -o "$T/tws.exr" "$T/tw.exr"
same "a twill is the same one cell along its diagonal" "$T/tws.exr" "$T/tw.exr"
t_xform --shift 20,0 --wrap -o "$T/twx.exr" "$T/tw.exr"
d=$(maxdiff "$T/twx.exr" "$T/tw.exr")
approx "$d" 0 0.1 && notok "a twill differs one cell across" || ok "a twill differs one cell across"
# Colours per thread, in turn: two warp colours share the warp's area.
t_weave -s 480 --thread-count 24 --thread-width 1 --irregularity 0 --warp-colours '#ff0000,#00ff00' \
    --weft-colours '#0000ff' -o "$T/two.exr"
r=$(t_op -t 0.01 threshold "$T/two.exr" | info_json - stats 0 mean)
g=$(t_op -t 0.01 threshold "$T/two.exr" | info_json - stats 1 mean)
approx "$r" 0.25 0.01 && approx "$g" 0.25 0.01 && ok "two warp colours in turn, each a quarter ($r, $g)" ||
    notok "two warp colours in turn" "$r, $g"
# Gaps between narrow threads are dark; the height map is 0 there and highest on top.
t_weave -s 480 --thread-count 24 --thread-width 0.6 --irregularity 0 --map height -o "$T/h.exr"
approx "$(info_json "$T/h.exr" stats 0 min)" 0 0 && approx "$(info_json "$T/h.exr" stats 0 max)" 1 0.02 &&
    ok "height: 0 in the gaps, 1 on the top threads' crowns" || notok "height range"
# Irregularity changes the threads; the same seed gives the same map, another seed another.
t_weave -s 200 --irregularity 0.5 -S 3 -j 1 -o "$T/i1.exr"
t_weave -s 200 --irregularity 0.5 -S 3 -j 2 -o "$T/i2.exr"
same "the same map on 1 and 2 threads" "$T/i1.exr" "$T/i2.exr"
t_weave -s 200 --irregularity 0.5 -S 4 -o "$T/i3.exr"
d=$(maxdiff "$T/i1.exr" "$T/i3.exr")
approx "$d" 0 0.01 && notok "another seed, other yarns" || ok "another seed, other yarns"
t_weave -s 200 --irregularity 0 -S 3 -o "$T/i0.exr"
t_weave -s 200 --irregularity 0 -S 4 -o "$T/i4.exr"
same "without irregularity the seed does not matter" "$T/i0.exr" "$T/i4.exr"
# --tile: whole repeats of the weave and the colours, so the last thread runs into the first.
check "--tile with 20 threads of a 4-thread twill" t_weave -s 40 --thread-count 20 --weave twill --tile -o "$T/t.exr"
check_fails "--tile with 10 threads of a 4-thread twill" 2 t_weave -s 40 --thread-count 10 --weave twill --tile
check_fails "--tile with 20 threads of 3 colours" 2 t_weave -s 40 --thread-count 20 --warp-colours '#ff0000,#00ff00,#0000ff' --tile
# In a scene, as a texture.
printf 'camera { eye 0 0 -3 look 0 0 0 }\nlight distant { direction 0 0 -1 }\ntexture c weave { weave satin thread-count 40 }\nsurface s { apply c { Kd = f } }\nsphere { surface s }\n' >"$T/s.scene"
check "a scene renders a weave" t_apply -s 64 --spp 1 -o "$T/r.png" "$T/s.scene"
# Bad values: one line, exit 2, nothing written.
check_fails "a twill's float as long as its repeat" 2 t_weave --weave twill --shafts 4 --float 4 -o "$T/x.exr"
check_fails "a satin of 6 shafts" 2 t_weave --weave satin --shafts 6 -o "$T/x.exr"
check_fails "2 shafts" 2 t_weave --weave twill --shafts 2 -o "$T/x.exr"
check_fails "a colour by name" 2 t_weave --warp-colours red -o "$T/x.exr"
check_fails "an empty colour list" 2 t_weave --weft-colours '' -o "$T/x.exr"
check_fails "65 colours" 2 t_weave --warp-colours "$(printf '#102030,%.0s' $(seq 64))#405060" -o "$T/x.exr"
check "nothing written" test ! -e "$T/x.exr"
