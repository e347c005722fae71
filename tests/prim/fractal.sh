#!/usr/bin/env bash
# tests/prim/fractal.sh - t_fractal's modes and the stochastic models from the command line.
. "$(dirname "$0")/../lib.sh"

for m in fbm ridged hybrid midpoint mandelbrot julia koch; do
    # PFM: the pixels alone (an EXR's history holds the command line).
    t_fractal -s 64 -m "$m" -S 3 -j 1 -o "$T/$m.1.exr" && t_convert -o "$T/$m.1.pfm" "$T/$m.1.exr" &&
        t_fractal -s 64 -m "$m" -S 3 -j 2 --format pfm >"$T/$m.2.pfm" &&
        TEXTURA_SIMD=scalar t_fractal -s 64 -m "$m" -S 3 --format pfm >"$T/$m.3.pfm"
    if cmp -s "$T/$m.1.pfm" "$T/$m.2.pfm" && cmp -s "$T/$m.1.pfm" "$T/$m.3.pfm"; then
        ok "fractal $m: same bytes across threads and SIMD levels"
    else
        notok "fractal $m" "bytes differ"
    fi
    lo=$(info_json "$T/$m.1.exr" stats 0 min)
    hi=$(info_json "$T/$m.1.exr" stats 0 max)
    if approx "$lo" 0.5 0.5 && approx "$hi" 0.5 0.5 && awk -v a="$lo" -v b="$hi" 'BEGIN{exit !(b > a)}'; then
        ok "fractal $m in [0,1] and not constant ($lo..$hi)"
    else
        notok "fractal $m range" "$lo..$hi"
    fi
done
for t in holes colorvar perturb; do
    if t_$t -s 48 -j 1 --format pfm >"$T/$t.1" && t_$t -s 48 -j 2 --format pfm >"$T/$t.2" && cmp -s "$T/$t.1" "$T/$t.2"; then
        ok "$t: same bytes with 1 and 2 threads"
    else
        notok "$t determinism"
    fi
    # the portable path's bytes (colorvar's and perturb's sines go four at a time: base/trig.h)
    TEXTURA_SIMD=scalar t_$t -s 48 -j 1 --format pfm >"$T/$t.3" && cmp -s "$T/$t.1" "$T/$t.3" &&
        ok "$t: TEXTURA_SIMD=scalar gives the same bytes" || notok "$t under TEXTURA_SIMD=scalar"
done
# Holes against goldens made by searching every neighbouring cell, before the search
# skipped the cells beyond the nearest hole: large jittered holes, small tiled ones, and
# solid holes on a sphere in t_apply (the cells above and below count there).
t_holes -s 96 --grid-cells 5 --diameter 1 --jitter 1 -S 2 -o "$T/h_large.exr"
golden "holes: large jittered holes golden" "$T/h_large.exr" holes_large.exr 1e-6
t_holes -s 96 --grid-cells 12 --diameter 0.3 --probability 0.5 --tile -S 3 -o "$T/h_small.exr"
golden "holes: small tiled holes golden" "$T/h_small.exr" holes_small.exr 1e-6
cat >"$T/holes.scene" <<'SCENE'
image 96 96
ambient 1 1 1
camera { eye 0 0 -4 look 0 0 0 fov 50 }
texture h holes { solid grid_cells 4 diameter 1 jitter 0.8 seed 5 }
surface s { Ka 1 Kd 1 apply h { mapping solid Kd = f } }
sphere { centre 0 0 0 radius 1.5 surface s }
SCENE
t_apply "$T/holes.scene" -q -o "$T/h_solid.exr"
golden "holes: solid holes on a sphere golden" "$T/h_solid.exr" holes_solid.exr 1e-6
t_colorvar -s 16 --colour '#ff8000' -o "$T/c.exr"
if [ "$(info_json "$T/c.exr" channels)" = 3 ] && [ "$(info_json "$T/c.exr" stats 2 max)" = 0 ]; then
    ok "colorvar --colour scales the colour"
else
    notok "colorvar --colour" "$(t_info "$T/c.exr" | head -5)"
fi
# The thesis's orange peel: h per level.
check "midpoint orange peel" t_fractal -m midpoint --h 10,0,0,0,0,0,-10,10 -s 64 -o "$T/peel.exr"
# Koch: the centre of the snowflake is inside, a corner outside.
t_fractal -m koch -s 33 --recursions 3 -o "$T/k.exr"
if [ "$(info_json "$T/k.exr" stats 0 max)" = 1 ] && approx "$(info_json "$T/k.exr" stats 0 mean)" 0.45 0.15; then
    ok "koch snowflake fills part of the map"
else
    notok "koch" "$(t_info "$T/k.exr" | head -3)"
fi

# --band-limit: octaves whose cells are far larger than a pixel are untouched, so a
# coarse map is the same bytes; a fine one keeps its mean and loses its aliased roughness.
roughness() { # mean |difference| of horizontal neighbours in a 1-channel PFM
    python3 -c '
import struct, sys
d = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, d[1].split()); v = struct.unpack("<%df" % (w * h), d[3][:4 * w * h])
print(sum(abs(v[i + 1] - v[i]) for i in range(len(v) - 1) if (i + 1) % w) / (h * (w - 1)))' "$1"
}
for tool in "t_fractal" "t_turbulence"; do
    $tool -n 3 -f 2 -s 256 -o "$T/a.pfm"
    $tool -n 3 -f 2 -s 256 --band-limit -o "$T/b.pfm"
    cmp -s "$T/a.pfm" "$T/b.pfm" && ok "$tool --band-limit leaves coarse octaves alone" ||
        notok "$tool --band-limit changed a map whose cells are 32 pixels and more"
    $tool -n 8 -f 64 -s 256 -o "$T/a.pfm"
    $tool -n 8 -f 64 -s 256 --band-limit -o "$T/b.pfm"
    ma=$(info_json "$T/a.pfm" stats 0 mean) mb=$(info_json "$T/b.pfm" stats 0 mean)
    ra=$(roughness "$T/a.pfm") rb=$(roughness "$T/b.pfm")
    if approx "$ma" "$mb" 0.01 && awk -v a="$ra" -v b="$rb" 'BEGIN { exit !(b < 0.75 * a) }'; then
        ok "$tool --band-limit: same mean ($ma, $mb), less aliasing (roughness $ra -> $rb)"
    else
        notok "$tool --band-limit" "mean $ma -> $mb, roughness $ra -> $rb"
    fi
done
check_fails "--band-limit is fbm's" 2 t_fractal -m ridged --band-limit
check_fails "octaves 0" 2 t_fractal -n 0
check_fails "octaves 1000" 2 t_fractal -n 1000
check_fails "negative frequency" 2 t_fractal -f -2
check_fails "NaN gain" 2 t_fractal --ridge-gain nan
check_fails "malformed --h" 2 t_fractal -m midpoint --h 10,,0
check_fails "--h not a number" 2 t_fractal -m midpoint --h 1,x
check_fails "--h too long" 2 t_fractal -m midpoint --h 1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1
check_fails "unknown mode" 2 t_fractal -m spiral
check_fails "mandelbrot cannot tile" 2 t_fractal -m mandelbrot --tile
check_fails "zero zoom" 2 t_fractal -m julia --zoom 0
check_fails "holes count 0" 2 t_holes --grid-cells 0
check_fails "perturb fractional stripes with --tile" 2 t_perturb --tile --stripes 2.5
check_fails "colorvar bad colour" 2 t_colorvar --colour '#12'
