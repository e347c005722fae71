#!/bin/bash
# t_apply: command line, output, and bad scenes (file:line:column, exit status, no output)
. tests/lib.sh

good=tests/scenes/spheres.scene
check "renders a shipped test scene" t_apply "$good" -s 64x48 -o "$T/a.png"
check "scene then options order" t_apply -o "$T/b.exr" -s 40x30 --spp 2 -j 2 "$good"
w=$(info_json "$T/b.exr" width)
[ "$w" = 40 ] && ok "-s overrides the scene's image size" || notok "-s overrides" "width $w"
t_apply "$good" -s 40x30 -j 1 -o "$T/j1.exr" && t_apply "$good" -s 40x30 -j 2 -o "$T/j2.exr"
t_convert -o "$T/j1.pfm" "$T/j1.exr" && t_convert -o "$T/j2.pfm" "$T/j2.exr"
cmp -s "$T/j1.pfm" "$T/j2.pfm" && ok "same bytes with -j 1 and -j 2" || notok "determinism across -j"
# A scanline EXR is rendered and written in bands of rows (t_apply.c): the pixels of the
# whole render (PFM, made whole), on a pipe and in a file, at a height that bands of 64 rows
# do not divide, in a region too, with -j 1 and -j 2 (farm.sh assembles regions so made).
for v in "whole|" "region|--region 3,50,37,90"; do
    name=${v%%|*} args=${v#*|}
    # shellcheck disable=SC2086
    if t_apply "$good" -s 41x150 -j 1 $args --format pfm >"$T/bw-$name.pfm" &&
        t_apply "$good" -s 41x150 -j 2 $args -o - | t_convert -o "$T/bp-$name.pfm" - &&
        t_apply "$good" -s 41x150 -j 1 $args -o "$T/bf-$name.exr" &&
        t_convert -o "$T/bf-$name.pfm" "$T/bf-$name.exr"; then
        cmp -s "$T/bw-$name.pfm" "$T/bp-$name.pfm" && cmp -s "$T/bw-$name.pfm" "$T/bf-$name.pfm" &&
            ok "$name: the EXR made in bands has the whole render's pixels" ||
            notok "$name: bands against the whole render" \
                "$(maxdiff "$T/bw-$name.pfm" "$T/bp-$name.pfm")"
    else
        notok "$name: renders in bands"
    fi
done
# The vector paths (AVX2: trilinear lookups of colour maps, 3D noise at points) give the
# scalar path's bytes: a colour map to the horizon (every mip level, blended), its bump,
# and solid turbulence.
t_noise -s 96x64 -f 5 | t_palette marble -o "$T/col.exr"
cat >"$T/simd.scene" <<SCENE
image 48 36
camera { eye 0 1 -3 look 0 0.7 8 fov 60 }
light point { position -3 6 -4 }
texture col file "$T/col.exr"
texture veins turbulence { solid frequency 3 octaves 6 seed 2 }
surface floor { Kd 1 1 1 apply col { mapping planar scale 0.5 Kd = f bump = 0.4 } }
surface stone { Kd 0.8 0.8 0.8 apply veins { mapping solid Kd = 0.2 + 0.8 * f } }
plane { surface floor }
sphere { centre 0 1 3 radius 1 surface stone }
SCENE
simd=$(grep -qw avx2 /proc/cpuinfo && echo avx2 || echo "scalar only: no AVX2 here")
if t_apply "$T/simd.scene" -j 1 --format pfm >"$T/v.pfm" &&
    TEXTURA_SIMD=scalar t_apply "$T/simd.scene" -j 1 --format pfm >"$T/s.pfm"; then
    sd=$(info_json "$T/v.pfm" stats 0 stddev)
    cmp -s "$T/v.pfm" "$T/s.pfm" && awk -v s="$sd" 'BEGIN { exit !(s > 0.05) }' &&
        ok "a textured render has the scalar path's bytes ($simd; stddev $sd)" ||
        notok "vector against scalar render" "$(maxdiff "$T/v.pfm" "$T/s.pfm"), stddev $sd"
else
    notok "vector against scalar render: renders"
fi
# Bump mapping, N' = N - s grad f: a sinusoid f = 0.5 + 0.5 sin(2 pi u) on a plane seen from
# straight above, u = x / 8, lit from (1, 1, 0): each pixel's light is the flat render's times
# N'.L / N.L, with grad f = (pi / 8) cos(pi x / 4) along x at the pixel's hit x, both for the
# map (its lookup's own derivatives) and for the same sinusoid made at the hit (finite
# differences); a wrong sign or scale of the gradient fails it.
t_expr -s 256x4 '0.5 + 0.5 * sin(2 * pi * u)' -o "$T/wave.exr"
export T
cat >"$T/pfm.py" <<'PY'
import struct
def pfm(p):  # width, height, the RGB floats, rows bottom up
    f = open(p, "rb"); f.readline(); w, h = map(int, f.readline().split()); s = float(f.readline())
    return w, h, struct.unpack(("<" if s < 0 else ">") + "f" * (w * h * 3), f.read())
PY
for b in 0 1.2; do
    cat >"$T/bump$b.scene" <<SCENE
image 64 4
ambient 0 0 0
camera { eye 2 4 0 look 2 0 0 up 0 0 1 fov 28 }
light distant { direction 1 1 0 }
texture wave file "$T/wave.exr"
primitive ripple() = 0.5 + 0.5 * sin(2 * pi * u)
texture made ripple { }
surface map { Ka 0 Kd 1 1 1 apply wave { mapping planar scale 0.125 bump = $b } }
surface made { Ka 0 Kd 1 1 1 apply made { mapping planar scale 0.125 bump = $b } }
plane { surface map }
SCENE
    sed 's/plane { surface map }/plane { surface made }/' "$T/bump$b.scene" >"$T/made$b.scene"
done
bump_ok() { # NAME FLAT BUMPED: every pixel of the middle rows within 0.01 of the formula
    python3 - "$2" "$3" <<'PY' && ok "$1" || notok "$1" "$(cat "$T/.bump")"
import math, os, sys
sys.path.insert(0, os.environ["T"])
from pfm import pfm
w, h, flat = pfm(sys.argv[1]); _, _, bump = pfm(sys.argv[2])
flat, bump = flat[::3], bump[::3]  # red
sx = math.tan(math.radians(28) / 2); L = (1 / math.sqrt(2), 1 / math.sqrt(2), 0)
worst = 0
for row in (1, 2):
    for i in range(w):
        x = 2 + 4 * ((i + 0.5) * 2 * sx / w - sx)  # the hit's x: the plane 4 below the eye
        g = 1.2 * (math.pi / 8) * math.cos(math.pi * x / 4)
        n = (-g, 1, 0); ln = math.sqrt(g * g + 1)
        want = flat[row * w + i] * ((n[0] * L[0] + n[1] * L[1]) / ln) / L[1]
        worst = max(worst, abs(bump[row * w + i] - want))
open(os.environ["T"] + "/.bump", "w").write("worst %.4f" % worst)
sys.exit(worst > 0.01)
PY
}
for s in bump made; do
    t_apply "$T/${s}0.scene" -j 1 --format pfm >"$T/${s}0.pfm" &&
        t_apply "$T/${s}1.2.scene" -j 1 --format pfm >"$T/${s}1.pfm"
done
bump_ok "a map's bump tilts the normal by its gradient (N' = N - s grad f)" "$T/bump0.pfm" "$T/bump1.pfm"
bump_ok "a primitive's bump, by finite differences, does the same" "$T/made0.pfm" "$T/made1.pfm"
# A spot light lights its cone alone: seen from above, the floor under it is lit and the
# image's corners, 52 degrees off its 10-degree axis, get nothing at all (no ambient).  The
# spot first (its direction made ahead of the material, render.c) and after a distant light
# from below the floor, which adds nothing: the same bytes.
for first in 1 0; do
    lights='light spot { position 0 4 0 at 0 0 0 angle 10 }'
    [ $first = 1 ] || lights="light distant { direction 0 -1 0 }
$lights"
    cat >"$T/spot$first.scene" <<SCENE
image 33 33
ambient 0 0 0
camera { eye 0 10 0 look 0 0 0 up 0 0 1 fov 40 }
$lights
surface floor { Ka 0 Kd 1 1 1 }
plane { surface floor }
SCENE
    t_apply "$T/spot$first.scene" -j 1 --format pfm >"$T/spot$first.pfm" || notok "spot: renders"
done
if python3 - "$T/spot1.pfm" <<'PY'; then
import os, sys
sys.path.insert(0, os.environ["T"])
from pfm import pfm
w, h, px = pfm(sys.argv[1])
red = lambda x, y: px[3 * (y * w + x)]
corners = [red(x, y) for x in (0, w - 1) for y in (0, h - 1)]
sys.exit(not (red(w // 2, h // 2) > 0.5 and corners == [0, 0, 0, 0]))
PY
    cmp -s "$T/spot1.pfm" "$T/spot0.pfm" &&
        ok "a spot light lights its cone and nothing beyond, first or second" ||
        notok "a spot light second against first" "$(maxdiff "$T/spot1.pfm" "$T/spot0.pfm")"
else
    notok "a spot light: lit under it, dark beyond its cone"
fi
# The map's gradient through each kind of mapping derivative (a turned plane's planar
# mapping, a box's and a turned sphere's natural ones) against the same sinusoids in u and
# v made at the hit, whose bump takes finite differences: on average within a tenth of what
# the bump changes (they part only by the two methods' discretisation).
ripple='0.5 + 0.25 * sin(2 * pi * u) + 0.25 * sin(2 * pi * v)'
t_expr -s 256 "$ripple" -o "$T/wave2.exr"
for shape in wall box sphere; do
    case $shape in
    wall) obj='plane { surface S rotate -90 0 0 translate 0 0 3 }' map='mapping planar scale 0.125' ;;
    box) obj='box { min -2 -1.5 0 max 2 1.5 1 surface S }' map='mapping natural' ;;
    sphere) obj='sphere { centre 0 0 0 radius 1.4 surface S rotate 0 30 0 }' map='mapping natural' ;;
    esac
    for v in "wave 0.4" "made 0.4" "wave 0"; do
        cat >"$T/$shape.scene" <<SCENE
image 96 72
ambient 0 0 0
camera { eye 0.3 0.2 -4 look 0 0 0 fov 50 }
light distant { direction 1 1 -1 }
texture wave file "$T/wave2.exr"
primitive ripple() = $ripple
texture made ripple { }
surface S { Ka 0 Kd 1 1 1 apply ${v% *} { $map bump = ${v#* } } }
$obj
SCENE
        t_apply "$T/$shape.scene" -j 1 -q --format pfm >"$T/$shape-${v% *}-${v#* }.pfm"
    done
    python3 - "$T/$shape-wave-0.4.pfm" "$T/$shape-made-0.4.pfm" "$T/$shape-wave-0.pfm" \
        >"$T/.bump" <<'PY' && ok "$shape: a map's bump agrees with finite differences" ||
import os, sys
sys.path.insert(0, os.environ["T"])
from pfm import pfm
a, b, c = (pfm(p)[2] for p in sys.argv[1:4])
apart = sum(abs(x - y) for x, y in zip(a, b)) / len(a)
effect = sum(abs(x - y) for x, y in zip(a, c)) / len(a)
print("mean |map - differences| %.5f, mean bump %.5f" % (apart, effect))
sys.exit(not (effect > 0.01 and apart < 0.1 * effect))
PY
        notok "$shape: a map's bump agrees with finite differences" "$(cat "$T/.bump")"
done
t_noise -s 64 -o "$T/noise.exr"
for f in patterns/*.scene tests/scenes/*.scene; do
    if t_apply "$f" -s 32x24 --spp 1 -o "$T/s.exr" <"$T/noise.exr" 2>"$T/s.err"; then
        ok "shipped scene $f renders"
    else
        notok "shipped scene $f renders" "$(cat "$T/s.err")"
    fi
done

# bad input: each must fail with one line naming file:line:column and leave no file
bad() {
    local name=$1 status=$2 text=$3
    printf '%s\n' "$text" >"$T/bad.scene"
    check_fails "$name" "$status" t_apply "$T/bad.scene" -o "$T/bad.png"
    if [ -e "$T/bad.png" ]; then notok "$name: no output file"; rm -f "$T/bad.png"; fi
    if [ "$status" != 0 ] && ! grep -q "bad.scene:[0-9]*:[0-9]*:" "$T/.err"; then
        notok "$name: message names file:line:column" "$(cat "$T/.err")"
    fi
}
bad "syntax error" 2 'camera { eye 0 0 -5 look 0 0 0'
bad "unknown word" 2 'sphere { radius 1 colour 1 }'
bad "unknown surface" 2 'sphere { surface nosuch }'
bad "unknown texture in apply" 2 'surface s { apply wood { Kd = f } }'
bad "unknown name in an expression" 2 'texture t noise { } surface s { apply t { Kd = g } }'
bad "unknown primitive" 2 'texture t nosuchprim { }'
bad "bad primitive parameter" 2 'texture t noise { frequency -3 }'
bad "missing map file" 1 'texture t file "/nonexistent/map.png"'
bad "sphere radius 0" 2 'sphere { radius 0 }'
bad "cylinder of zero length" 2 'cylinder { base 0 1 0 top 0 1 0 }'
bad "box min > max" 2 'box { min 1 1 1 max 0 0 0 }'
bad "NaN as a number" 2 'sphere { radius nan }'
bad "huge number" 2 'sphere { radius 1e999 }'
bad "absurd image size" 2 'image 100000 100000'
bad "samples 0" 2 'samples 0'
bad "eye equals look" 2 'camera { eye 0 0 0 look 0 0 0 }'
bad "scale by zero" 2 'sphere { scale 0 }'
bad "single CSG child" 2 'union { sphere { } }'
bad "unterminated string" 2 'texture t file "abc'
bad "nested too deeply" 2 "$(for i in $(seq 70); do printf 'union { sphere { } '; done)"
# the lexer's words for where a scene went wrong, as a composition script's (lang/lex.h)
said() { # said NAME TEXT WANT: the message of scene TEXT holds WANT
    printf '%s' "$2" >"$T/said.scene"
    t_apply "$T/said.scene" -o "$T/said.png" 2>"$T/said.err"
    grep -qF -- "$3" "$T/said.err" && ok "$1" || notok "$1" "$(cat "$T/said.err")"
}
said "a block cut short says so" 'camera { eye 0 0 -5' \
    "said.scene:1:20: expected '}' to end the camera, found the end of the file"
said "a CSG block cut short says so" 'union { sphere { }' \
    "expected '}' to end a union, found the end of the file"
said "a scene that ends too soon: the end of the file" 'texture t' \
    "expected 'file' or a primitive name, found the end of the file"
said "a long token quoted to 32 characters" "surface s { Ka $(printf 'a%.0s' $(seq 60)) }" \
    "expected a number, found '$(printf 'a%.0s' $(seq 32))'"
check_fails "missing scene file" 1 t_apply "$T/none.scene" -o "$T/x.png"
check_fails "absurd -s" 2 t_apply "$good" -s 0x5 -o "$T/x.png"
# an output name without a format is refused before the scene is read (and rendered)
check_fails "unknown output extension" 2 t_apply "$T/none.scene" -o "$T/x.foo"
grep -q "x.foo: cannot tell the format" "$T/.err" && ok "the output's format is checked first" ||
    notok "output format checked first" "$(cat "$T/.err")"

printf 'camera { eye 0 0 0 look 0 0 1 }\nsphere { radius 2 }\n' >"$T/in.scene"
t_apply "$T/in.scene" -s 8 -o "$T/in.exr" 2>"$T/in.err"
grep -q "in.scene:2:1: warning: the camera is inside" "$T/in.err" && [ -e "$T/in.exr" ] &&
    ok "camera inside an object: a warning with its place" || notok "camera inside warning" "$(cat "$T/in.err")"
printf 'camera { eye 0 0 0 look 0 0 1 }\nsurface water { Kd 0 Ks 0 Kt 1 ior 1.33 }\nsphere { radius 2 surface water }\n' \
    >"$T/under.scene"
t_apply "$T/under.scene" -s 8 -o "$T/under.exr" 2>"$T/under.err" && [ ! -s "$T/under.err" ] &&
    ok "camera inside a transparent solid: its medium, no warning" ||
    notok "camera in water" "$(cat "$T/under.err")"

# a map on standard input
t_noise -s 64 | t_apply tests/scenes/stdin.scene -s 32x24 -o "$T/stdin.exr" &&
    ok "texture '-' reads the map from standard input" || notok "texture from standard input"

# big CSG: a union of 100,000 spheres renders (a balanced tree, then a BVH over its operands:
# no walk recurses along the list), and as the same spheres as separate objects do
awk 'BEGIN { srand(1); print "camera { eye 0 0 -60 look 0 0 0 fov 50 }\nlight distant { direction 1 1 -1 }";
    printf "union {\n" >"/dev/stderr";
    for (i = 0; i < 100000; i++) { s = sprintf("sphere { centre %.3f %.3f %.3f radius 0.15 }",
        rand() * 40 - 20, rand() * 30 - 15, rand() * 40 - 20); print s; print s >"/dev/stderr" }
    print "}" >"/dev/stderr" }' >"$T/sep.scene" 2>"$T/union.body"
{ head -2 "$T/sep.scene"; cat "$T/union.body"; } >"$T/union.scene"
t_apply "$T/union.scene" -s 32x24 -o "$T/union.pfm" && t_apply "$T/sep.scene" -s 32x24 -o "$T/sep.pfm" &&
    cmp -s "$T/union.pfm" "$T/sep.pfm" && ok "a union of 100,000 spheres renders, as the spheres do apart" ||
    notok "a union of 100,000 spheres"
for op in intersection difference; do
    { echo "camera { eye 0 0 -6 look 0 0 0 }"; echo "$op {";
      for i in $(seq 20000); do echo "sphere { radius 1.5 }"; done; echo "}"; } >"$T/chain.scene"
    check "$op of 20,000 objects renders" t_apply "$T/chain.scene" -s 16x12 -o "$T/chain.png"
done

# a placed world mapping: the scene turned 90 degrees about x, with the mapping placed by
# the same turn, renders as the scene does unturned, mip-mapped footprints too (the
# footprint's u and v gradients are the placed mapping's); so does the turned scene with a
# solid mapping, whose u and v there are the world mapping's on the floor (x and z)
world_scene() { # EYE LOOK UP TURN MAPPING PLACED
    cat <<SCENE
image 160 120
samples 1
ambient 1 1 1
camera { eye $1 look $2 up $3 fov 60 }
texture c checker { nu 2 nv 2 size 64 }
surface s { Ka 1 Kd 1 apply c { mapping $5 scale 2 $6 Kd = f } }
plane { surface s $4 }
SCENE
}
max_diff() { # the largest difference between two PFMs
    python3 -c '
import struct, sys
def rd(f):
    d = open(f, "rb").read().split(b"\n", 3); w, h = map(int, d[1].split())
    return struct.unpack("<%df" % (3 * w * h), d[3][:12 * w * h])
a, b = rd(sys.argv[1]), rd(sys.argv[2])
print("%.6f" % max(abs(x - y) for x, y in zip(a, b)))' "$1" "$2"
}
world_scene "0 1 -3" "0 0.7 8" "0 1 0" "" world "" >"$T/w0.scene"
world_scene "0 3 1" "0 -8 0.7" "0 0 1" "rotate 90 0 0" world "rotate 90 0 0" >"$T/w1.scene"
world_scene "0 3 1" "0 -8 0.7" "0 0 1" "rotate 90 0 0" solid "" >"$T/w2.scene"
if t_apply "$T/w0.scene" -q -o "$T/w0.pfm" && t_apply "$T/w1.scene" -q -o "$T/w1.pfm" &&
    t_apply "$T/w2.scene" -q -o "$T/w2.pfm"; then
    for k in 1 2; do
        d=$(max_diff "$T/w0.pfm" "$T/w$k.pfm")
        what=$([ $k = 1 ] && echo "a placed world mapping's" || echo "a solid mapping's")
        awk -v d="$d" 'BEGIN { exit !(d < 1e-4) }' &&
            ok "$what footprint turns with it (largest difference $d)" ||
            notok "$what footprint" "the turned scene differs by up to $d"
    done
else
    notok "placed world mapping scenes render"
fi
