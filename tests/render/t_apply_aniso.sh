#!/usr/bin/env bash
# t_apply's anisotropic models (issue 62): the highlight stretches along the tangent, the
# tangent from the mapping, a fixed direction, an angle and a flow field; spectral metals;
# the same bytes for any -j and on every path; bad input.
. "$(dirname "$0")/../lib.sh"
export TEXTURA_MATERIALS=patterns/materials.txt
pfm_py

# sphere MODEL SURFACE-WORDS [APPLY]: a black sphere lit from beside the eye, its highlight
# alone (Kd 0, no ambient), seen head-on; its natural mapping's u runs round the y axis
sphere() {
    cat <<EOS
image 96 96
ambient 0 0 0
camera { eye 0 0 -4 look 0 0 0 fov 32 }
light point { position 0.6 0.6 -4 }
texture n noise { }
surface s { model $1 Kd 0 material stainless specular 1 $2 ${3:+apply n { $3 \}} }
sphere { surface s }
EOS
}

# extent MAP: the highlight's width and height in pixels (those above half its peak)
extent() {
    py - "$1" <<'P'
import sys, pfm
a, w, h = pfm.load(sys.argv[1])
lum = [[sum(pfm.px(a, w, h, x, y, c) for c in range(3)) for x in range(w)] for y in range(h)]
top = max(max(r) for r in lum)
xs = [x for y in range(h) for x in range(w) if lum[y][x] > top / 2]
ys = [y for y in range(h) for x in range(w) if lum[y][x] > top / 2]
print(max(xs) - min(xs) + 1, max(ys) - min(ys) + 1)
P
}

# stretched NAME MAP across|along: the highlight is at least twice as wide as high (along
# u, across the view) or twice as high as wide
stretched() {
    local e w h
    e=$(extent "$2") || { notok "$1" "no highlight"; return; }
    read -r w h <<<"$e"
    if [ "$3" = across ]; then [ "$w" -ge $((2 * h)) ]; else [ "$h" -ge $((2 * w)) ]; fi &&
        ok "$1 (highlight ${w} x ${h} px)" || notok "$1" "highlight ${w} x ${h} px"
}

for m in ward ashikhmin-shirley; do
    sphere $m 'alpha 0.4 0.05' >"$T/$m-u.scene"
    sphere $m 'alpha 0.4 0.05 tangent v' >"$T/$m-v.scene"
    sphere $m 'alpha 0.4 0.05' 'angle = 90' >"$T/$m-a.scene"
    sphere $m 'alpha 0.4 0.05' 'tangent = rgb(0.5, 1, 0.5)' >"$T/$m-f.scene"
    sphere $m 'alpha 0.4 0.05 tangent 0 1 0' >"$T/$m-y.scene"
    sphere $m 'alpha 0.2' >"$T/$m-i.scene"
    for k in u v a f y i; do
        t_apply "$T/$m-$k.scene" -q -o "$T/$m-$k.pfm" || notok "$m-$k renders"
    done
    stretched "$m: rough along the mapping's u, the highlight stretches round the sphere" \
        "$T/$m-u.pfm" across
    stretched "$m: tangent v turns it up the sphere" "$T/$m-v.pfm" along
    stretched "$m: angle = 90 turns it up the sphere" "$T/$m-a.pfm" along
    stretched "$m: a flow field against v turns it up the sphere" "$T/$m-f.pfm" along
    stretched "$m: a fixed world tangent 0 1 0 turns it up the sphere" "$T/$m-y.pfm" along
    read -r w h <<<"$(extent "$T/$m-i.pfm")"
    [ "$((w - h))" -le 2 ] && [ "$((h - w))" -le 2 ] && ok "$m: alpha 0.2 alone is round (${w} x ${h})" ||
        notok "$m: one roughness gives a round highlight" "${w} x ${h}"
    # the two tangents come by differences of different steps: within 1e-3 of the peak (2)
    same "$m: angle = 90 and a flow field against v give the same pixels" "$T/$m-a.pfm" \
        "$T/$m-f.pfm" 2e-3
    sphere $m 'alpha 0.05' 'au = 0.4' >"$T/$m-au.scene"
    t_apply "$T/$m-au.scene" -q -o "$T/$m-au.pfm" &&
        same "$m: au = 0.4 over alpha 0.05 gives alpha 0.4 0.05's pixels" "$T/$m-au.pfm" \
            "$T/$m-u.pfm" 0 || notok "$m: au = 0.4 renders"
done

# a spectral gold cylinder brushed along its axis; a swirl by an angle of the position
cat >"$T/gold.scene" <<'EOS'
colour spectral 8
image 64 48
ambient 0.05 0.05 0.05
camera { eye 0 1 -4 look 0 0 0 fov 40 }
light point { position -2 3 -4 }
light point { position 3 1 -3 intensity 0.5 }
texture n noise { }
surface g { model ward material gold specular 0.9 Kd 0.3 alpha 0.3 0.06
            apply n { mapping planar angle = 30 * sin(4 * x) + 20 * f au = 0.2 + 0.2 * f } }
surface p { model ashikhmin-shirley material silver alpha 0.05 0.5 tangent 1 0 0 Kd 0.4 }
cylinder { base 0 -1 0 top 0 1 0 radius 0.8 surface g }
plane { distance -1 surface p }
EOS
check "a spectral gold cylinder and a silver plane render" t_apply "$T/gold.scene" -q -o "$T/gold.exr"
r=$(info_json "$T/gold.exr" stats 0 mean) b=$(info_json "$T/gold.exr" stats 2 mean)
awk -v r="$r" -v b="$b" 'BEGIN { exit !(r > 1.3 * b) }' && ok "spectral gold is warm (R $r B $b)" ||
    notok "spectral gold is warm" "R $r B $b"
t_apply "$T/gold.scene" -q -j 1 -o "$T/gold1.pfm" && t_apply "$T/gold.scene" -q -j 2 -o "$T/gold2.pfm" &&
    cmp -s "$T/gold1.pfm" "$T/gold2.pfm" && ok "-j 1 and -j 2 give the same bytes" ||
    notok "-j 1 against -j 2" "$(maxdiff "$T/gold1.pfm" "$T/gold2.pfm")"
same_paths gold "$T/gold.scene"
sed 's/colour spectral 8/colour rgb/' "$T/gold.scene" >"$T/rgb.scene"
same_paths rgb "$T/rgb.scene"
same_paths flow "$T/ward-f.scene"
# a flow field from a map file (mip-mapped, looked up ahead with the packets) and a fixed
# tangent, at 64 x 42
t_noise -s 64 -f 3 -S 5 --tile | t_filter normal --strength 30 -o "$T/flow.exr"
sed -e 's|file -|file "'"$T"'/flow.exr"|' -e 's/^image .*/image 64 42/' -e 's/^samples .*/samples 1/' \
    -e '/^surface ball/s/material stainless/& tangent -1 0.5 0/' patterns/brushed_steel.scene \
    >"$T/steel.scene"
same_paths brushed_steel "$T/steel.scene"

# bad input: one line naming the scene's line and the range
bad() {
    printf '%s\n' "$2" >"$T/bad.scene"
    check_fails "$1" 2 t_apply "$T/bad.scene" -o "$T/bad.exr"
    grep -q "${3:-bad.scene:}" "$T/.err" || notok "$1: names the line" "$(cat "$T/.err")"
}
bad "a negative roughness is refused" 'surface s { model ward alpha -0.1 0.2 }' \
    'bad.scene:1:.*0.001..1'
bad "a roughness above 1 is refused" 'surface s { model ward alpha 0.2 1.5 }' \
    'bad.scene:1:.*0.001..1'
bad "a zero tangent is refused" 'surface s { model ward tangent 0 0 0 }' 'bad.scene:1:'
bad "a tangent along a plane's normal is refused" \
    "$(printf 'surface s {\n model ward tangent 0 2 0 }\nplane { surface s }')" \
    'bad.scene:1:.*line 3'
bad "a tangent word must be u, v or X Y Z" 'surface s { model ward tangent w }' 'u|v|X Y Z'
bad "au needs an anisotropic model" \
    "$(printf 'texture n noise { }\nsurface s { apply n { au = f } }')" 'ward or ashikhmin'
bad "alpha 0 is refused" \
    "$(printf 'texture n noise { }\nsurface s { model ward apply n { au = f } alpha 0 }')" \
    'bad.scene:2:.*0.001..1'
