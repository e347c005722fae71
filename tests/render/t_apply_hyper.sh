#!/usr/bin/env bash
# t_apply's hypertextures (thesis 2.9): the shipped recipes (fireball, eroded sphere, smoke
# over CSG) as goldens, the same bytes at any -j, SIMD level and region, and bad input as
# one line naming the scene line.  The marcher's analytic cases are test_render_hyper's.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}

for sc in fireball eroded_sphere smoke_csg; do
    t_apply "$top/patterns/$sc.scene" -s 48x36 --spp 1 -q -o "$T/$sc.exr" &&
        golden "patterns/$sc.scene golden" "$T/$sc.exr" "apply_$sc.exr" 1e-5 ||
        notok "patterns/$sc.scene renders"
done

# the same bytes at -j 1 and -j 2, on the portable path, and in a region of the image
sc=$top/patterns/smoke_csg.scene
if t_apply "$sc" -s 40x30 --spp 2 -j 1 -q -o "$T/j1.pfm" &&
    t_apply "$sc" -s 40x30 --spp 2 -j 2 -q -o "$T/j2.pfm" &&
    TEXTURA_SIMD=scalar t_apply "$sc" -s 40x30 --spp 2 -j 2 -q -o "$T/sc.pfm"; then
    cmp -s "$T/j1.pfm" "$T/j2.pfm" && ok "-j 1 and -j 2 give the same bytes" ||
        notok "-j 1 and -j 2 give the same bytes"
    cmp -s "$T/j1.pfm" "$T/sc.pfm" && ok "TEXTURA_SIMD=scalar gives the same bytes" ||
        notok "TEXTURA_SIMD=scalar gives the same bytes"
else
    notok "smoke_csg renders at -j 1 and -j 2"
fi

bad() { # NAME SCENE-TEXT LINE: exit 2, one line, naming bad.scene:LINE:
    printf 'image 4 4\n%s\n' "$2" >"$T/bad.scene"
    check_fails "$1" 2 t_apply "$T/bad.scene" -o "$T/bad.png"
    [ -e "$T/bad.png" ] && notok "$1: no output file"
    grep -q "bad.scene:$3:[0-9]*:" "$T/.err" || notok "$1: names line $3" "$(cat "$T/.err")"
}
bad "a negative density coefficient" 'hypertexture { sphere { }
  scattering -2 }' 3
bad "a step of 0" 'hypertexture { sphere { } step 0 }' 2
bad "an unbounded volume" 'light point { position 0 3 0 }
hypertexture { complement { box { } } }' 3
bad "a soft width past the centre" 'hypertexture { sphere { radius 0.5 soft 2 } }' 2
bad "a phase past 1" 'hypertexture { sphere { } phase 1 }' 2
bad "H in the density that makes it" 'hypertexture { sphere { } density = H }' 2
bad "a surface's quantity" 'hypertexture { sphere { } opacity = ndotv }' 2
bad "an unknown texture" 'hypertexture { sphere { } density = D * nosuch }' 2
bad "two densities" 'hypertexture { sphere { } sphere { } }' 2
bad "no density" 'hypertexture { absorption 2 }' 2
bad "a boolean of one" 'hypertexture { union { sphere { } } }' 2
