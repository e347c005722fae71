#!/bin/bash
# region.sh - t_apply --region against the whole render, assembled by t_assemble
. "${TEXTURA_TOP:-.}/tests/lib.sh"

t_noise -s 64 -o "$T/noise.exr"
# Regions of uneven sizes, with jittered samples (seeded per pixel), put back together.
regions() {
    local name=$1 scene=$2 parts=() ok=1
    shift 2
    t_apply "$scene" -s 75x53 "$@" -o "$T/whole.exr" <"$T/noise.exr" ||
        { notok "$name" "whole render failed"; return; }
    for r in 0,0,30,20 30,0,45,20 0,20,75,1 0,21,13,32 13,21,62,32; do
        t_apply "$scene" -s 75x53 "$@" --region $r -o "$T/r$r.exr" <"$T/noise.exr" || ok=0
        parts+=("$T/r$r.exr")
    done
    [ $ok = 1 ] || { notok "$name" "a region failed"; return; }
    t_assemble "${parts[@]}" -o "$T/as.exr" || { notok "$name" "t_assemble failed"; return; }
    same "$name" "$T/as.exr" "$T/whole.exr"
}
regions "regions == whole render (spheres, 4 samples)" tests/scenes/spheres.scene --spp 4
regions "regions == whole render (five spheres, -j 1)" patterns/five_spheres.scene --spp 2 -j 1
regions "regions == whole render (area light)" patterns/still_life.scene --spp 1
regions "regions == whole render (hypertexture over CSG)" patterns/smoke_csg.scene --spp 2

t_apply tests/scenes/spheres.scene -s 40x30 --region 8,4,10,6 -o "$T/one.exr"
check "a region records its place in the image" \
    bash -c "oiiotool --info -v '$T/one.exr' | grep -q 'pixel data origin: x=8, y=4'"
check "a region as PNG (no place kept) renders" \
    t_apply tests/scenes/spheres.scene -s 40x30 --region 8,4,10,6 -o "$T/one.png"

check_fails "region outside the image" 2 t_apply tests/scenes/spheres.scene -s 40x30 \
    --region 35,0,10,10 -o "$T/bad.exr"
check_fails "region of zero size" 2 t_apply tests/scenes/spheres.scene -s 40x30 \
    --region 0,0,10,0 -o "$T/bad.exr"
check_fails "malformed region" 2 t_apply tests/scenes/spheres.scene --region 1,2 -o "$T/bad.exr"
[ -e "$T/bad.exr" ] && notok "no output after a bad region" || ok "no output after a bad region"
