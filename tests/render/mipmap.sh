#!/bin/bash
# mipmap.sh - tiled and mip-mapped EXR output, read back by oiiotool and by t_apply
. "${TEXTURA_TOP:-.}/tests/lib.sh"

t_noise -s 300x200 -o "$T/flat.exr"
t_noise -s 300x200 --mipmap -o "$T/mip.exr"
t_noise -s 300x200 --exr-tiles -o "$T/tiled.exr"
info=$(oiiotool --info -v "$T/mip.exr")
grep -q "MIP-map levels: 300x200 150x100 75x50 37x25 18x12 9x6 4x3 2x1 1x1" <<<"$info" &&
    ok "oiiotool --info -v shows the mip levels" || notok "oiiotool shows the mip levels" "$info"
grep -q "tile size: 64 x 64" <<<"$info" && ok "--mipmap is tiled 64 x 64" ||
    notok "--mipmap is tiled 64 x 64"
info=$(oiiotool --info -v "$T/tiled.exr")
grep -q "tile size: 64 x 64" <<<"$info" && ! grep -q "MIP-map" <<<"$info" &&
    ok "--exr-tiles: one level of 64 x 64 tiles" || notok "--exr-tiles: one level of tiles" "$info"
same "the top level is the map" "$T/mip.exr" "$T/flat.exr"
same "--exr-tiles keeps the map" "$T/tiled.exr" "$T/flat.exr"
# Each level is the one above halved by a box filter, which t_xform --scale 0.5 also is
# for even sides; oiiotool reads each level (ZIP-compressed edge tiles included).
t_xform "$T/flat.exr" --scale 0.5 -o "$T/half.exr"
oiiotool "$T/mip.exr" --selectmip 1 -o "$T/l1.exr"
same "level 1 read by oiiotool is the map halved" "$T/l1.exr" "$T/half.exr"
t_xform "$T/half.exr" --scale 0.5 -o "$T/quarter.exr"
oiiotool "$T/mip.exr" --selectmip 2 -o "$T/l2.exr"
same "level 2 read by oiiotool is the map quartered" "$T/l2.exr" "$T/quarter.exr"
for l in 3 5 8; do
    oiiotool "$T/mip.exr" --selectmip $l -o "$T/l.exr"
    lo=$(info_json "$T/l.exr" stats 0 min) hi=$(info_json "$T/l.exr" stats 0 max)
    awk -v a="$lo" -v b="$hi" 'BEGIN { exit !(a >= 0.2 && b <= 0.8) }' &&
        ok "level $l holds noise values" || notok "level $l holds noise values" "$lo..$hi"
done
check "a mip-mapped stream through a pipe" bash -c "t_noise -s 100 --mipmap | t_info >/dev/null"
t_noise -s 100 --window 20,30,50,40 --mipmap -o "$T/wmip.exr"
check "a mip-mapped window keeps its place" \
    bash -c "oiiotool --info -v '$T/wmip.exr' | grep -q 'pixel data origin: x=20, y=30'"

# t_apply takes the levels of a mip-mapped file: ours are the pyramid it would build (the
# same image); maketx's are filtered otherwise (another image, same top level).
t_checker -s 300x200 --nu 16 --nv 16 -o "$T/ck.exr"
t_convert "$T/ck.exr" --mipmap -o "$T/ck_mip.exr"
scene() {
    printf 'camera { eye 0 1 -4 look 0 0 6 }\nlight distant { direction 1 1 -1 }\n'
    printf 'texture t file "%s"\nsurface s { apply t { mapping planar Kd = f } }\n' "$1"
    printf 'plane { surface s }\n'
}
scene "$T/ck.exr" >"$T/flat.scene"
scene "$T/ck_mip.exr" >"$T/mip.scene"
t_apply "$T/flat.scene" -s 80x60 -o "$T/r_flat.exr"
t_apply "$T/mip.scene" -s 80x60 -o "$T/r_mip.exr"
same "t_apply: a --mipmap file renders as the flat map" "$T/r_mip.exr" "$T/r_flat.exr"
if command -v maketx >/dev/null && maketx "$T/ck.exr" -o "$T/ck_tx.exr" >/dev/null 2>&1; then
    scene "$T/ck_tx.exr" >"$T/tx.scene"
    t_apply "$T/tx.scene" -s 80x60 -o "$T/r_tx.exr"
    d=$(maxdiff "$T/r_tx.exr" "$T/r_flat.exr")
    same "maketx's top level is the map" "$T/ck_tx.exr" "$T/ck.exr"
    approx "$d" 0 0.001 && notok "t_apply reads maketx's levels" "same image as the flat map" ||
        ok "t_apply reads maketx's levels (the image differs by $d)"
else
    skip "t_apply reads maketx's levels" "maketx is not installed or failed"
fi

check_fails "--mipmap to a non-EXR file" 2 t_noise -s 64 --mipmap -o "$T/bad.png"
check_fails "--exr-tiles to a non-EXR file" 2 t_noise -s 64 --exr-tiles -o "$T/bad.tif"
check_fails "--mipmap to a non-EXR standard output" 2 \
    bash -c "set -o pipefail; t_noise -s 64 --mipmap --format png | cat >/dev/null"
check_fails "--mipmap of region ids" 2 t_ring -s 64 --ids --mipmap -o "$T/bad.exr"
[ -e "$T/bad.png" ] || [ -e "$T/bad.tif" ] || [ -e "$T/bad.exr" ] &&
    notok "no output after bad --mipmap" || ok "no output after bad --mipmap"
