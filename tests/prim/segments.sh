#!/usr/bin/env bash
# t_segments: the thesis's nearly parallel line segments (section 4.5, Figure 4.7), as a map
# and as a solid texture: range, direction, coverage, seams, determinism and bad values.
. "$(dirname "$0")/../lib.sh"

# mean MAP CHANNEL: the mean of a channel
mean() { info_json "$1" stats "$2" mean; }

t_segments -s 512 -o "$T/a.exr"
approx "$(info_json "$T/a.exr" stats 0 min)" 0 0 && approx "$(info_json "$T/a.exr" stats 0 max)" 1 1e-3 &&
    ok "values in [0,1], 0 between the grooves and 1 on their axes" || notok "range"
# Direction: grooves along u change across v, not along u; and the other way at 90 degrees.
for a in 0 90; do
    t_segments -s 512 --angle $a --angle-spread 2 | t_filter gradient | t_op abs - -o "$T/g$a.exr"
done
gu=$(mean "$T/g0.exr" 0) gv=$(mean "$T/g0.exr" 1)
awk -v u="$gu" -v v="$gv" 'BEGIN { exit !(v > 8 * u) }' && ok "angle 0: the grooves run along u ($gv across, $gu along)" ||
    notok "angle 0 runs along u" "$gv across, $gu along"
gu=$(mean "$T/g90.exr" 0) gv=$(mean "$T/g90.exr" 1)
awk -v u="$gu" -v v="$gv" 'BEGIN { exit !(u > 8 * v) }' && ok "angle 90: the grooves run along v" ||
    notok "angle 90 runs along v" "$gu across, $gv along"
# A wider spread mixes the directions.
t_segments -s 512 --angle 0 --angle-spread 90 | t_filter gradient | t_op abs - -o "$T/gs.exr"
gu=$(mean "$T/gs.exr" 0) gv=$(mean "$T/gs.exr" 1)
awk -v u="$gu" -v v="$gv" 'BEGIN { exit !(v < 2 * u) }' && ok "a spread of 90 degrees has no direction" ||
    notok "spread 90" "$gv across, $gu along"
# Coverage: N segments per unit square, each a capsule of area L W + pi W^2 / 4, cover
# 1 - e^(-N A) of the map (a Poisson field of them).
for set in "300 0.2 0.004" "2000 0.05 0.006" "100 0.5 0.01"; do
    read -r n l w <<<"$set"
    t_segments -s 512 --segments "$n" --length "$l" --width "$w" -S 3 | t_op -t 1e-9 threshold - -o "$T/c.exr"
    got=$(mean "$T/c.exr" 0)
    want=$(awk -v n="$n" -v l="$l" -v w="$w" 'BEGIN { print 1 - exp(-n * (l * w + 3.14159265 * w * w / 4)) }')
    awk -v g="$got" -v e="$want" 'BEGIN { d = g / e - 1; exit !(d < 0.12 && d > -0.12) }' &&
        ok "N $n, L $l, W $w covers $got of the map (Poisson: $want)" ||
        notok "coverage of N $n, L $l, W $w" "$got against $want"
done
# --tile: the grooves cross the seam; without it the edges are unrelated.
seam() { # MAP: mean |last column - first column| over the mean of two inner neighbours
    t_xform --clip 511,0,512,512 -o "$T/l.exr" "$1"
    t_xform --clip 0,0,1,512 -o "$T/f.exr" "$1"
    t_xform --clip 200,0,201,512 -o "$T/i0.exr" "$1"
    t_xform --clip 201,0,202,512 -o "$T/i1.exr" "$1"
    awk -v s="$(t_op sub "$T/l.exr" "$T/f.exr" | t_op abs - | info_json - stats 0 mean)" \
        -v i="$(t_op sub "$T/i0.exr" "$T/i1.exr" | t_op abs - | info_json - stats 0 mean)" 'BEGIN { print s / (i + 1e-6) }'
}
t_segments -s 512 --segments 600 --width 0.01 --tile -o "$T/t.exr"
t_segments -s 512 --segments 600 --width 0.01 -o "$T/n.exr"
st=$(seam "$T/t.exr") sn=$(seam "$T/n.exr")
awk -v t="$st" -v n="$sn" 'BEGIN { exit !(t < 1.5 && n > 5) }' && ok "--tile: no seam ($st against $sn without)" ||
    notok "--tile: no seam" "$st with, $sn without"
# The same seed gives the same bytes, whatever the threads; another seed another map.
t_segments -s 300x200 -S 9 -j 1 -o "$T/j1.exr"
t_segments -s 300x200 -S 9 -j 2 -o "$T/j2.exr"
same "the same map on 1 and 2 threads" "$T/j1.exr" "$T/j2.exr"
t_segments -s 300x200 -S 10 -o "$T/s10.exr"
cmp -s "$T/j1.exr" "$T/s10.exr" && notok "another seed, another map" || ok "another seed, another map"
t_segments -s 300x200 -S 9 --window 100,50,64,32 -o "$T/w.exr"
t_xform --clip 100,50,164,82 -o "$T/wc.exr" "$T/j1.exr"
same "a window is the same pixels as the whole map's" "$T/w.exr" "$T/wc.exr"
# As a solid texture: the grooves in space, streaks on a plane along their direction.
cat >"$T/s.scene" <<S
camera { eye 0 3 0 look 0 0 0 up 0 0 1 fov 40 }
light distant { direction 0 1 0 }
ambient 0.2 0.2 0.2
texture g segments { solid tile segments 2000 length 0.4 width 0.02 }
surface s { Kd 0.8 apply g { mapping world Kd = 0.8 * (1 - f) } }
plane { normal 0 1 0 distance 0 surface s }
S
check "a scene renders the solid segments" t_apply -s 128 --spp 1 -o "$T/r.exr" "$T/s.scene"
t_filter gradient "$T/r.exr" | t_op abs - -o "$T/rg.exr"
gu=$(mean "$T/rg.exr" 0) gv=$(mean "$T/rg.exr" 1)
awk -v u="$gu" -v v="$gv" 'BEGIN { exit !(u > 3 * v || v > 3 * u) }' && ok "the solid grooves on a plane are streaks ($gu, $gv)" ||
    notok "solid grooves are streaks" "$gu, $gv"
# Bad values: one line, exit 2, nothing written.
check_fails "no segments" 2 t_segments --segments 0 -o "$T/x.exr"
check_fails "a width of 0" 2 t_segments --width 0 -o "$T/x.exr"
check_fails "too many for their length" 2 t_segments --segments 1000000 --length 0.9 -o "$T/x.exr"
check "nothing written" test ! -e "$T/x.exr"
