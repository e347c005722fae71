#!/bin/bash
# farm.sh - patterns/farm.sh under GNU parallel -j 2 equals the single process, byte for byte
. "${TEXTURA_TOP:-.}/tests/lib.sh"
top=${TEXTURA_TOP:-.}
if ! command -v parallel >/dev/null; then
    skip "patterns/farm.sh under GNU parallel" "GNU parallel is not installed (make deps installs it)"
    exit 0
fi
# Pixels byte for byte: PFM holds the floats as they are (the EXR histories differ).
bytes_same() {
    t_convert "$2" -o "$T/a.pfm" && t_convert "$3" -o "$T/b.pfm" && cmp -s "$T/a.pfm" "$T/b.pfm" &&
        ok "$1" || notok "$1" "$(cmp "$T/a.pfm" "$T/b.pfm" 2>&1)"
}

"$top/patterns/farm.sh" map -o "$T/map.exr" -s 203x150 -n 5 -j 2 -- t_turbulence -S 3 -f 5 \
    >"$T/out" 2>&1 || notok "farm.sh map runs" "$(head -c 300 "$T/out")"
t_turbulence -S 3 -f 5 -s 203x150 -o "$T/map1.exr"
bytes_same "farm.sh map (5 bands, parallel -j 2) == one process" "$T/map.exr" "$T/map1.exr"

FARM_ASSEMBLE=--exr-tiles "$top/patterns/farm.sh" map -o "$T/ring.exr" -s 96 -n 3 -j 2 -- \
    t_ring --nu 3 --nv 2 >/dev/null 2>&1
t_ring --nu 3 --nv 2 -s 96 -o "$T/ring1.exr"
bytes_same "farm.sh map of a geometric primitive, tiled == one process" "$T/ring.exr" "$T/ring1.exr"

t_noise -s 64 -o "$T/noise.exr"
"$top/patterns/farm.sh" render -o "$T/img.exr" -s 90x60 -n 4 -j 2 -- \
    t_apply "$top/tests/scenes/spheres.scene" --spp 4 <"$T/noise.exr" >"$T/out" 2>&1 ||
    notok "farm.sh render runs" "$(head -c 300 "$T/out")"
t_apply "$top/tests/scenes/spheres.scene" --spp 4 -s 90x60 -o "$T/img1.exr"
bytes_same "farm.sh render (4 row bands, parallel -j 2) == one render" "$T/img.exr" "$T/img1.exr"

"$top/patterns/farm.sh" frames -o "$T/fr" -n 6 -j 2 -- t_noise -s 48 >/dev/null 2>&1
t_noise -s 48 --frames 6 --frame 4 -o "$T/fr4.exr"
bytes_same "farm.sh frames == the frame made alone" "$T/fr_4.exr" "$T/fr4.exr"
[ -e "$T/fr_0.exr" ] && [ -e "$T/fr_5.exr" ] && ok "farm.sh frames writes every frame" ||
    notok "farm.sh frames writes every frame"

"$top/patterns/farm.sh" map -o "$T/bad.exr" -s 64 -n 2 -- t_spectral >/dev/null 2>&1
[ $? != 0 ] && [ ! -e "$T/bad.exr" ] && ok "farm.sh fails when a piece fails, leaving no output" ||
    notok "farm.sh fails when a piece fails"
"$top/patterns/farm.sh" tiles -o "$T/bad.exr" -- t_noise 2>/dev/null
[ $? = 2 ] && ok "farm.sh refuses an unknown mode (exit 2)" || notok "farm.sh unknown mode"
"$top/patterns/farm.sh" map -o "$T/bad.exr" -s 64 -n 0 -- t_noise 2>/dev/null
[ $? = 2 ] && ok "farm.sh refuses -n 0 (exit 2)" || notok "farm.sh -n 0"
