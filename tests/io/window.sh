#!/bin/bash
# window.sh - every generator's --window against the whole map; t_assemble; bad windows
. "${TEXTURA_TOP:-.}/tests/lib.sh"

# Four windows of uneven sizes put back together equal the whole map, pixel for pixel.
four() {
    local name=$1
    shift
    local W=97 H=61 parts=() ok=1
    "$@" -s ${W}x$H -o "$T/whole.exr" || { notok "$name windows" "whole map failed"; return; }
    for win in 0,0,40,25 40,0,57,25 0,25,40,36 40,25,57,36; do
        "$@" -s ${W}x$H --window $win -o "$T/w$win.exr" || ok=0
        parts+=("$T/w$win.exr")
    done
    [ $ok = 1 ] || { notok "$name windows" "a window failed"; return; }
    t_assemble "${parts[@]}" -o "$T/as.exr" || { notok "$name windows" "t_assemble failed"; return; }
    same "$name: four windows assembled == the whole map" "$T/as.exr" "$T/whole.exr"
}

for t in noise turbulence d_noise colorvar holes perturb wood bubble; do
    four t_$t t_$t
done
for t in brick checker circle cycloid dots ellipse flower four_rings grid hypocycloid polygon \
    ring star stripe; do
    four "t_$t (colour)" t_$t
done
four "t_ring --ids" t_ring --ids
four "t_noise --tile -f 4 --z 0.3" t_noise --tile -f 4 --z 0.3
four "t_noise 4D (--w)" t_noise --w 0.7
four "t_bubble --value f2-f1 -j 1" t_bubble --value f2-f1 -j 1
for mode in fbm ridged hybrid mandelbrot julia koch; do
    four "t_fractal --mode $mode" t_fractal --mode $mode
done

# A window of a window's row band equals the same rows cut from the whole (one band only).
t_noise -s 64 --window 0,10,64,1 -o "$T/band.exr"
check "a one-row band has its place in the map" \
    bash -c "oiiotool --info -v '$T/band.exr' | grep -q 'pixel data origin: x=0, y=10'"

# The stream through a pipe keeps the place; t_assemble writes the stream too.
t_noise -s 50 --window 0,0,50,20 | t_convert -o "$T/p1.exr"
t_noise -s 50 --window 0,20,50,30 -o "$T/p2.exr"
t_noise -s 50 -o "$T/p.exr"
t_assemble "$T/p1.exr" "$T/p2.exr" | t_convert -o "$T/pa.exr"
same "windows through pipes, assembled to standard output" "$T/pa.exr" "$T/p.exr"

# Bad input: one message, exit 2, no output left behind.
check_fails "window outside the map" 2 t_noise -s 64 --window 60,0,8,8 -o "$T/bad.exr"
check_fails "window of zero size" 2 t_noise -s 64 --window 0,0,0,8 -o "$T/bad.exr"
check_fails "malformed window" 2 t_noise -s 64 --window 0,0,8 -o "$T/bad.exr"
check_fails "negative window" 2 t_noise -s 64 --window -1,0,8,8 -o "$T/bad.exr"
check_fails "spectral cannot window" 2 t_spectral -s 64 --window 0,0,8,8 -o "$T/bad.exr"
check_fails "midpoint cannot window" 2 t_fractal --mode midpoint -s 64 --window 0,0,8,8 \
    -o "$T/bad.exr"
[ -e "$T/bad.exr" ] && notok "no output after bad windows" || ok "no output after bad windows"
check_fails "t_assemble: a gap" 2 t_assemble "$T/p1.exr" -o "$T/bad.exr"
check_fails "t_assemble: an overlap" 2 t_assemble "$T/p1.exr" "$T/p1.exr" "$T/p2.exr" \
    -o "$T/bad.exr"
t_noise -s 40 --window 0,0,40,20 -o "$T/o1.exr"
check_fails "t_assemble: windows of different maps" 2 t_assemble "$T/o1.exr" "$T/p2.exr" \
    -o "$T/bad.exr"
check_fails "t_assemble: not EXR" 2 t_assemble "$T/p1.exr" "$T/p2.exr" -o "$T/bad.png"
[ -e "$T/bad.exr" ] || [ -e "$T/bad.png" ] && notok "t_assemble leaves no output on error" ||
    ok "t_assemble leaves no output on error"
t_noise -s 32 -o "$T/sample.exr"
check_fails "sparse convolution cannot window" 2 t_sparse "$T/sample.exr" -s 64 \
    --window 0,0,8,8 -o "$T/bad.exr"

# A tiled assembly (64 x 64 tiles, bands of tile rows) equals the whole map.
t_assemble "$T/p1.exr" "$T/p2.exr" --exr-tiles -o "$T/pt.exr"
check "t_assemble --exr-tiles writes tiles" bash -c "oiiotool --info -v '$T/pt.exr' | grep -q 'tile size: 64 x 64'"
same "t_assemble --exr-tiles == the whole map" "$T/pt.exr" "$T/p.exr"
check_fails "t_assemble --exr-tiles to a pipe" 2 bash -c "set -o pipefail; t_assemble '$T/p1.exr' '$T/p2.exr' --exr-tiles | cat >/dev/null"
check_fails "t_assemble --mipmap" 2 t_assemble "$T/p1.exr" "$T/p2.exr" --mipmap -o "$T/bad.exr"
