#!/usr/bin/env bash
# tests/prim/noise.sh - t_noise, t_d_noise, t_turbulence from the command line: determinism across
# threads and SIMD levels, tiling options, large coordinates, bad input.
. "$(dirname "$0")/../lib.sh"

# same_bytes NAME CMD...: CMD run with -j 1, -j 2, TEXTURA_SIMD=scalar and (where the CPU has
# AVX-512, whose rows the others use) TEXTURA_SIMD=avx2 writes identical pixels (as PFM: the
# EXR's history holds the differing command lines).
same_bytes() {
    local name=$1
    shift
    "$@" -j 1 --format pfm >"$T/a.pfm" && "$@" -j 2 --format pfm >"$T/b.pfm" &&
        TEXTURA_SIMD=scalar "$@" -j 2 --format pfm >"$T/c.pfm" &&
        TEXTURA_SIMD=avx2 "$@" -j 1 --format pfm >"$T/d.pfm" || { notok "$name" "command failed"; return; }
    if cmp -s "$T/a.pfm" "$T/b.pfm" && cmp -s "$T/a.pfm" "$T/c.pfm" && cmp -s "$T/a.pfm" "$T/d.pfm"; then
        ok "$name: same bytes for -j 1, -j 2, scalar and AVX2 SIMD"
    else
        notok "$name" "bytes differ between thread counts or SIMD levels"
    fi
}

same_bytes "noise 2D" t_noise -s 203x67 -f 13 -S 5
same_bytes "noise 3D slice" t_noise -s 130 -f 7 --z 0.37 --offset 0.5,2.25
same_bytes "noise 4D" t_noise -s 96 -f 3 --w 0.6 --fade quintic
same_bytes "noise far away" t_noise -s 64 -f 9 --offset 1e6,-3e7,2e6
same_bytes "noise tile" t_noise -s 64 -f 4 --tile
same_bytes "noise more cells than pixels" t_noise -s 50 -f 333
same_bytes "turbulence" t_turbulence -s 100 -n 7
same_bytes "d_noise" t_d_noise -s 40 --channels 3
same_bytes "d_noise wide, quintic, far away" t_d_noise -s 1030x24 -f 300 --channels 3 --fade quintic --offset 1e6,2e6 --z 0.3
same_bytes "d_noise normal map, tile" t_d_noise -s 67x45 -f 5 --normal --strength 2 --tile
# The octave rows' fast paths: cells wider than 8 pixels (broadcasts), 1-8 pixels (permutes),
# narrower (gathers); lattice rows kept for the next pixel rows (cells taller than a pixel) or
# not; more than one column chunk (1024); a width not a multiple of 8; every row operation.
same_bytes "fbm, every kernel path" t_fractal -s 1100x40 -f 3 -n 10 -l 2.3 -S 4
# rows wider than the lattice table, octaves finer than pixels: the folded table rows
same_bytes "turbulence, fine octaves on wide rows" t_turbulence -s 1030x40 -f 300 -n 6 -S 2
same_bytes "ridged, fine octaves on wide rows" t_fractal -m ridged -s 1500x30 -f 700 -n 5
same_bytes "hybrid, fine octaves on wide rows" t_fractal -m hybrid -s 1500x30 -f 520 -n 4 --fade quintic
# cells of 1.2 to 5 pixels on rows with a table (tall enough) and wider than it: planar folded rows
same_bytes "fbm, folded rows of cells 1.2-5 pixels wide" t_fractal -s 1100x200 -f 300 -n 3 -S 3
same_bytes "turbulence, folded rows, 7 columns past sixteen" t_turbulence -s 1031x160 -f 700 -n 2 --z 0.3
# cells of one pixel, then half a pixel: permutes of one register's coefficients, then two's
same_bytes "turbulence, folded rows of cells 1 and 1/2 pixel wide" t_turbulence -s 1040x260 -f 1040 -n 2 --offset 0.37,0.21
same_bytes "noise, cells finer than pixels on wide rows" t_noise -s 1200x32 -f 2000 --z 0.4
same_bytes "fbm quintic 4D" t_fractal -s 97x61 -f 5 -n 5 --w 0.3 --fade quintic --z 0.2
same_bytes "turbulence 4D quintic" t_turbulence -s 333x50 -f 5 -n 6 --w 0.3 --fade quintic
same_bytes "turbulence tile far away" t_turbulence -s 130x70 -f 4 --tile --offset 1e6,-2e6,3
same_bytes "ridged" t_fractal -m ridged -s 257x40 -f 6 -n 7 -l 2.5 --ridge-gain 3
same_bytes "hybrid tile" t_fractal -m hybrid -s 200x48 -f 4 --tile --mf-offset 0.7
same_bytes "one octave of fbm" t_fractal -s 77x20 -n 1
same_bytes "one octave of turbulence" t_turbulence -s 77x20 -n 1
# Thirty octaves at lacunarity 16 from frequency 1e6 reach 1e41 cycles: the top octaves sit on
# lattice points (0), the map stays finite, and the sanitizer build checks the float-to-int casts.
same_bytes "fbm past 2^62 cycles" t_fractal -s 64x16 -f 1e6 -n 30 -l 16
same_bytes "turbulence past 2^62 cycles" t_turbulence -s 64x16 -f 1e6 -n 30 -l 16 --z 1e9 --w 1e9
same_bytes "perturb" t_perturb -s 150x40 -n 6

check "same seed, same map" bash -c 't_noise -s 32 -S 9 --format pfm >"$0/x" && t_noise -s 32 -S 9 --format pfm >"$0/y" && cmp -s "$0/x" "$0/y"' "$T"
check "another seed, another map" bash -c 't_noise -s 32 -S 9 --format pfm >"$0/x" && t_noise -s 32 -S 10 --format pfm >"$0/y" && ! cmp -s "$0/x" "$0/y"' "$T"

# Far from the origin: no NaN and the texture is still there.
t_noise -s 64 -f 8 --offset 1e9,1e9 -o "$T/far.exr"
sd=$(info_json "$T/far.exr" stats 0 stddev)
nf=$(info_json "$T/far.exr" stats 0 nonfinite)
if [ "$nf" = 0 ] && approx "$sd" 0.09 0.05; then ok "noise at 1e9 keeps its texture (stddev $sd)"; else notok "noise at 1e9" "stddev $sd, nonfinite $nf"; fi

t_noise -s 128 -f 8 -o "$T/n.exr"
mean=$(info_json "$T/n.exr" stats 0 mean)
if approx "$mean" 0.5 0.04; then ok "noise mean near 0.5 ($mean)"; else notok "noise mean" "$mean"; fi

t_d_noise -s 32 --normal --strength 3 -o "$T/nm.exr"
if [ "$(info_json "$T/nm.exr" channels)" = 3 ] && approx "$(info_json "$T/nm.exr" stats 2 min)" 0.8 0.3; then
    ok "d_noise --normal writes 3 channels pointing outwards"
else
    notok "d_noise --normal" "$(t_info "$T/nm.exr" | head -4)"
fi
t_d_noise -s 16 -o "$T/g.exr"
if [ "$(info_json "$T/g.exr" channels)" = 2 ]; then ok "d_noise writes 2 channels"; else notok "d_noise channels"; fi

check_fails "negative frequency" 2 t_noise -f -1
check_fails "NaN frequency" 2 t_noise -f nan
check_fails "fractional frequency with --tile" 2 t_noise -f 2.5 --tile
check_fails "malformed offset" 2 t_noise --offset 1,,2
check_fails "too many offsets" 2 t_noise --offset 1,2,3,4
check_fails "unknown fade" 2 t_noise --fade linear
check_fails "turbulence octaves 0" 2 t_turbulence -n 0
check_fails "turbulence octaves 1000" 2 t_turbulence -n 1000
check_fails "turbulence fractional lacunarity with --tile" 2 t_turbulence --tile -l 2.5
check_fails "d_noise 4 channels" 2 t_d_noise --channels 4
# the help states the range a map has (issue 64: "rescaled to [0,1]" while a map spans
# about 0.24..0.75): the words and the figures agree
range=$(t_noise --help | sed -n 's/.*mostly \([0-9.]*\)\.\.\([0-9.]*\) in a map.*/\1 \2/p')
t_noise -s 512 -f 32 -S 9 -o "$T/range.exr"
lo=$(info_json "$T/range.exr" stats 0 min) hi=$(info_json "$T/range.exr" stats 0 max)
[ -n "$range" ] && awk -v r="$range" -v lo="$lo" -v hi="$hi" 'BEGIN { split(r, a, " ")
    exit !(lo >= a[1] - 0.05 && hi <= a[2] + 0.05 && lo < a[1] + 0.1 && hi > a[2] - 0.1) }' &&
    ok "t_noise's help states the range of its maps ($range; a map spans $lo..$hi)" ||
    notok "t_noise's stated range" "help '$range', map $lo..$hi"
