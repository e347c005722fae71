#!/bin/bash
# Scene parameters as rows (render_params.c): range messages in the scene's words,
# application functions clamped to the rows' ranges, t_apply(5)'s lists made from
# the rows, and seed/size with one limit in tools, scenes and scripts.
. tests/lib.sh

# says NAME STATUS 'scene' 'exact message after "t_apply: error: "'
says() {
    printf '%s\n' "$3" >"$T/p.scene"
    check_fails "$1" "$2" t_apply "$T/p.scene" -o "$T/p.png"
    if grep -qxF "t_apply: error: $T/p.scene:$4" "$T/.err"; then ok "$1: says '$4'"
    else notok "$1: message" "$(cat "$T/.err")"; fi
}
says "surface Ks above its range" 2 'surface s { Ks 5 }' '1:16: Ks must be 0..1 (got 5)'
says "surface Kd colour out of range" 2 'surface s { Kd 0.5 2 0 }' '1:16: Kd must be 0..1 (got 2)'
says "surface Kd of two numbers" 2 'surface s { Kd 0.5 0.5 }' '1:16: Kd takes 1 or 3 numbers (got 2)'
says "light angle above its range" 2 'light spot { at 0 0 1 angle 95 }' '1:29: angle must be 0.01..90 (got 95)'
says "area light samples not whole" 2 'light area { samples 2.5 }' '1:22: samples must be 1..32 (got 2.5)'
says "word of another light kind" 2 'light distant { angle 5 }' "1:17: unknown word 'angle' in a distant light"
says "camera fov above its range" 2 'camera { fov 180 }' '1:14: fov must be 0.01..179 (got 180)'
says "camera eye of two numbers" 2 'camera { eye 0 0 look 0 0 1 }' '1:14: eye takes 3 numbers (got 2)'
says "setting samples 0" 2 'samples 0' '1:9: samples must be 1..4096 (got 0)'
says "apply window above 1" 2 'texture t noise { } surface s { apply t { window 0 0 2 1 } }' \
    '1:50: window must be 0..1 (got 2)'
says "primitive parameter in scene words" 2 'texture t fractal { octaves 40 }' \
    '1:21: octaves must be 1..30 (got 40)'
says "scene seed above the limit" 2 'texture t noise { seed 2147483648 }' \
    '1:24: seed must be 0..2147483647 (got 2147483648)'
says "scene size above the limit" 2 'texture t noise { size 65537 }' \
    '1:24: size must be 1..65536 (got 65537)'

# the shapes' words are rows too (tex_object_rows): each shape takes its own only
says "word of another shape" 2 'sphere { major 1 }' "1:10: unknown word 'major' in a sphere"
says "a cone's word in a cylinder" 2 'cylinder { radius1 2 }' \
    "1:12: unknown word 'radius1' in a cylinder; did you mean radius?"
says "a torus's word in a box" 2 'box { axis 0 1 0 }' "1:7: unknown word 'axis' in a box"
says "a shape's checks keep their words" 2 'sphere { radius -1 }' '1:1: sphere radius must be > 0'
says "torus minor radius checked after the rows" 2 'torus { minor 0 }' \
    '1:1: torus minor radius must be > 0'
says "a shape's point of two numbers" 2 'sphere { centre 0 0 radius 1 }' \
    "1:21: expected a number, found 'radius'"

# the same rows on the command line (with dashes) and in a script (without)
check_fails "t_fractal --octaves 40" 2 t_fractal -s 8 --octaves 40 -o "$T/x.exr"
grep -qF -- "--octaves must be 1..30 (got '40')" "$T/.err" && ok "the command line names --octaves" ||
    notok "command-line message" "$(cat "$T/.err")"
script() { # script NAME 'call' 'message part'
    printf 'tessellation t; size 8 by 8;\nbuilt with (1,1) %s; end tessellation;\n' "$2" >"$T/p.tc"
    check_fails "script: $1" 2 t_compose -o "$T/p.exr" "$T/p.tc"
    if grep -qF -- "$3" "$T/.err" && ! grep -qF -- "--" "$T/.err"; then ok "script: $1 says '$3'"
    else notok "script: $1 message" "$(cat "$T/.err")"; fi
}
script "octaves 40" 'fractal(octaves = 40)' 'p.tc:2:26: octaves must be 1..30 (got 40)'
script "seed above the limit" 'noise(seed = 2147483648)' 'seed must be 0..2147483647 (got 2147483648)'
script "size above the limit" 'noise(size = 65537)' 'size must be 1..65536 (got 65537)'
script "tile 2" 'noise(tile = 2)' 'tile must be 0 or 1 (got 2)'
check_fails "t_noise -S 2147483648" 2 t_noise -s 8 -S 2147483648 -o "$T/x.exr"
grep -qF -- "--seed must be 0..2147483647" "$T/.err" && ok "-S has the same limit" ||
    notok "-S limit" "$(cat "$T/.err")"
check_fails "t_noise -s 65537" 2 t_noise -s 65537 -o "$T/x.exr"
grep -qF -- "1..65536" "$T/.err" && ok "-s has the same limit" || notok "-s limit" "$(cat "$T/.err")"
check "the largest seed is accepted in a tool" t_noise -s 8 -S 2147483647 -o "$T/x.exr"
printf 'texture t noise { seed 2147483647 size 8 }\nsphere { }\n' >"$T/seed.scene"
check "the largest seed is accepted in a scene" t_apply "$T/seed.scene" -s 8 -o "$T/x.exr"
printf 'tessellation t; size 8 by 8;\nbuilt with (1,1) noise(seed = 2147483647, tile = 0); end tessellation;\n' >"$T/seed.tc"
check "the largest seed is accepted in a script" t_compose -o "$T/x.exr" "$T/seed.tc"

# application-function results are clamped to the surface rows' ranges
render() { # render NAME 'surface body': a sphere lit from the eye's side, as PFM
    printf '%s\n' "image 24 24" "camera { eye 0 0 -4 look 0 0 0 fov 40 }" \
        "light point { position 2 3 -5 }" "texture t noise { size 8 }" \
        "surface s { $2 }" "sphere { surface s }" >"$T/$1.scene"
    t_apply "$T/$1.scene" -o "$T/$1.pfm" 2>"$T/.err" || notok "render $1" "$(cat "$T/.err")"
}
render ks5 'Kd 0.3 apply t { Ks = 5 + 0*f }'
render ks1 'Kd 0.3 apply t { Ks = 1 }'
render ks05 'Kd 0.3 apply t { Ks = 0.5 }'
render n1e9 'Kd 0.3 Ks 1 apply t { n = 1e9 + 0*f }'
render n1e4 'Kd 0.3 Ks 1 apply t { n = 10000 }'
cmp -s "$T/ks5.pfm" "$T/ks1.pfm" && ok "Ks = 5*... is clamped to the row's 1" ||
    notok "Ks clamped to 1"
cmp -s "$T/ks05.pfm" "$T/ks1.pfm" && notok "Ks 0.5 and 1 differ (the clamp test can fail)" ||
    ok "Ks 0.5 and 1 differ (the clamp test can fail)"
cmp -s "$T/n1e9.pfm" "$T/n1e4.pfm" && ok "n = 1e9 is clamped to the row's 10000" ||
    notok "n clamped to 10000"

# a constant function is folded (its channels' mean made once, render/appfn.c poly_of): the
# bytes of the same function evaluated at every hit (+ 0*f keeps it from folding)
render fold 'Kd 0.3 apply t { Ks = rgb(0.2, 0.5, 0.9) n = 30 Kr = 0.2 bump = rgb(0.1, 0.3, 0.8) }'
render nofold 'Kd 0.3 apply t { Ks = rgb(0.2, 0.5, 0.9) + 0*f n = 30 + 0*f Kr = 0.2 + 0*f
    bump = rgb(0.1, 0.3, 0.8) + 0*f }'
render fold2 'Kd 0.3 apply t { Ks = rgb(0.2, 0.5, 0.9) n = 30 Kr = 0.2 bump = rgb(0.1, 0.3, 0.9) }'
cmp -s "$T/fold.pfm" "$T/nofold.pfm" && ok "constant functions folded: the bytes evaluated per hit" ||
    notok "constant functions folded"
cmp -s "$T/fold.pfm" "$T/fold2.pfm" && notok "a folded bump's third channel counts" ||
    ok "a folded bump's third channel counts"

# a shape's defaults come from its rows: leaving a word out renders as writing its default
shape() { # shape NAME 'object block': lit from the eye's side, as PFM
    printf '%s\n' "image 32 24" "camera { eye 0 2 -5 look 0 0 0 fov 50 }" \
        "light point { position 2 3 -5 }" "surface s { Kd 0.8 0.5 0.2 Ks 0.4 }" \
        "$2" >"$T/$1.scene"
    t_apply "$T/$1.scene" -o "$T/$1.pfm" 2>"$T/.err" || notok "render $1" "$(cat "$T/.err")"
}
same_shape() { # same_shape SHAPE 'explicit defaults' [rotate: planes need a slant to be seen]
    shape "$1-def" "$1 { surface s ${3:-} }"
    shape "$1-exp" "$1 { $2 surface s ${3:-} }"
    cmp -s "$T/$1-def.pfm" "$T/$1-exp.pfm" && ok "$1: the rows' defaults render as written out" ||
        notok "$1: the rows' defaults render as written out"
}
same_shape sphere 'centre 0 0 0 radius 1'
same_shape box 'min -1 -1 -1 max 1 1 1' 'rotate 0 30 0'
same_shape cylinder 'base 0 0 0 top 0 1 0 radius 1'
same_shape cone 'base 0 0 0 top 0 1 0 radius1 1 radius2 0'
same_shape plane 'normal 0 1 0 distance 0' 'rotate 20 0 0'
same_shape torus 'centre 0 0 0 axis 0 1 0 major 1 minor 0.25'
same_shape inf_cone 'base 0 0 0 top 0 1 0 radius1 1 radius2 0'
shape torus-thick 'torus { minor 0.3 surface s }'
cmp -s "$T/torus-def.pfm" "$T/torus-thick.pfm" &&
    notok "torus minor 0.3 differs from the default (the test can fail)" ||
    ok "torus minor 0.3 differs from the default (the test can fail)"
shape sphere-centre 'sphere { centre 0.3 0 0 surface s }'
shape sphere-center 'sphere { center 0.3 0 0 surface s }'
cmp -s "$T/sphere-centre.pfm" "$T/sphere-center.pfm" && ! cmp -s "$T/sphere-centre.pfm" "$T/sphere-def.pfm" &&
    ok "center is another spelling of centre" || notok "center is another spelling of centre"
t_apply --help-scene object | grep -q '^  radius R .*(default 1)$' &&
    t_apply --help-scene object | grep -q '^  minor R .*(default 0.25)$' &&
    ok "--help-scene object lists radius and minor with their defaults" ||
    notok "--help-scene object" "$(t_apply --help-scene object | head -3)"

# t_apply(5)'s lists are the rows
t_apply --help-scene surface | grep -q '^  Ks K .*\[0..1\] (default 0)' &&
    ok "--help-scene surface lists Ks with its range and default" ||
    notok "--help-scene surface" "$(t_apply --help-scene surface | head -3)"
check_fails "--help-scene of no block" 2 t_apply --help-scene nosuch
man=$("$TEXTURA_TOP/tests/mkman" "$TEXTURA_BUILD/bin" --check 2>&1)
grep -q "^ok - man/man5/t_apply.5 " <<<"$man" && ok "t_apply(5) lists the rows of every scene block" ||
    notok "t_apply(5) lists the rows (run make man)" "$(grep t_apply <<<"$man")"
grep -c '^\.\\" begin options (generated by t_apply --help-scene-mdoc' \
    "$TEXTURA_TOP/man/man5/t_apply.5" | grep -qx 14 &&
    ok "t_apply(5) has a list per block, and of the quantities and functions" ||
    notok "t_apply(5) has a list per block"
lint=$(mandoc -Tlint -W warning "$TEXTURA_TOP/man/man5/t_apply.5" 2>&1)
[ -z "$lint" ] && ok "mandoc -Tlint t_apply(5) is clean" || notok "mandoc -Tlint t_apply(5)" "$lint"

# A primitive's own checks (its init, written once for every caller) speak the
# caller's language too: options on the command line, words in scenes and scripts.
printf 'camera { eye 0 0 -4 }\nlight point { position 0 3 -3 }\ntexture t fractal { mode mandelbrot tile }\nsurface s { Kd 1 1 1 apply t { Kd = f } }\nsphere { radius 1 surface s }\n' >"$T/init.scene"
check_fails "a primitive's init check in a scene" 2 t_apply "$T/init.scene" -s 8 -o "$T/x.exr"
grep -q 'init.scene:3:11: tile: mode mandelbrot is not periodic' "$T/.err" && ! grep -q -- '--' "$T/.err" &&
    ok "the init check names tile and mode as scene words" || notok "init check in a scene" "$(cat "$T/.err")"
printf 'tessellation t; size 32 by 32;\nbuilt with (1,1) noise(ids = 1); end tessellation;\n' >"$T/init.tc"
check_fails "a field check in a script" 2 t_compose "$T/init.tc" -o "$T/x.exr"
grep -q 'init.tc:2:18: noise has no subregions (ids)' "$T/.err" &&
    ok "the script's message names ids as a word" || notok "field check in a script" "$(cat "$T/.err")"
check_fails "the same check on the command line" 2 t_fractal --mode mandelbrot --tile -s 8 -o "$T/x.exr"
grep -q -- '--tile: --mode mandelbrot is not periodic' "$T/.err" &&
    ok "the command line keeps the option names" || notok "init check on the command line" "$(cat "$T/.err")"
