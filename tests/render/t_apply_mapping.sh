#!/usr/bin/env bash
# t_apply's mappings (thesis 5.3.1): the face id in application functions, fixed-size
# (non-elastic) mapping, P as a target and the infinite cone.
. "$(dirname "$0")/../lib.sh"

pfm_py # py: python3 with pfm.load and pfm.px (tests/lib.sh)

# counts MAP: "value count" of the red channel's values (rounded to 1e-4), one per line
counts() {
    py - "$1" <<'P'
import collections, sys, pfm
a, w, h = pfm.load(sys.argv[1])
for v, n in sorted(collections.Counter(round(a[i * 3], 4) for i in range(w * h)).items()):
    print(v, n)
P
}

# ---- face: the shape's face at the hit, whatever the mapping ----
face_scene() { # SHAPE KD
    cat <<S
image 64 48
camera { eye 2.2 2.6 -3 look 0 0.3 0 fov 50 }
ambient 1 1 1
texture n noise { }
surface s { Ka 1 Kd 1 apply n { mapping planar Kd = $2 } }
$1
S
}
# a box seen from (+x, +y, -z): faces 1 (+x), 3 (+y) and 6 (-z), and the sky (0)
face_scene 'box { min -1 -1 -1 max 1 1 1 surface s }' 'face / 6' >"$T/fbox.scene"
if t_apply "$T/fbox.scene" -o "$T/fbox.exr"; then
    got=$(counts "$T/fbox.exr" | awk '$2 > 50 { printf "%g ", $1 }')
    [ "$got" = "0 0.1667 0.5 1 " ] && ok "face: a box's +x, +y and -z faces are 1, 3 and 6" ||
        notok "face on a box" "values $got"
else
    notok "face on a box: renders"
fi
# a cylinder seen from above its top: the side 1, the top cap 3 (the bottom cap 2 is hidden)
face_scene 'cylinder { base 0 0 0 top 0 1 0 radius 1 surface s }' 'face / 3' >"$T/fcyl.scene"
if t_apply "$T/fcyl.scene" -o "$T/fcyl.exr"; then
    got=$(counts "$T/fcyl.exr" | awk '$2 > 50 { printf "%g ", $1 }')
    [ "$got" = "0 0.3333 1 " ] && ok "face: a cylinder's side is 1 and its top cap 3" ||
        notok "face on a cylinder" "values $got"
else
    notok "face on a cylinder: renders"
fi

# ---- size W H: a fixed-size (non-elastic) natural mapping ----
# wraps MAP CH: along the middle row, then the middle column, how many times channel CH
# wraps (jumps by more than 0.5), and CH's value at the centre
wraps() {
    py - "$1" "$2" <<'P'
import sys, pfm
a, w, h = pfm.load(sys.argv[1])
ch = int(sys.argv[2])
row = [pfm.px(a, w, h, x, h // 2, ch) for x in range(w)]
col = [pfm.px(a, w, h, w // 2, y, ch) for y in range(h)]
n = lambda s: sum(abs(s[i + 1] - s[i]) > 0.5 for i in range(len(s) - 1) if s[i] and s[i + 1])
print(n(row), n(col), pfm.px(a, w, h, w // 2, h // 2, ch))
P
}
size_scene() { # SHAPE APPLY-WORDS
    cat <<S
image 96 96
camera { eye 0 0 -40 look 0 0 0 fov 9 }
ambient 1 1 1
texture n noise { }
surface s { Ka 1 Kd 1 apply n { $2 Kd = rgb(u, v, footprint) } }
$1
S
}
# a box 4 x 2 (the unit box scaled 2, 1 per axis): its -z face is 8 maps of 0.5 x 0.25
# across and up, 7 wraps each way; the footprint, in the map's units, 8 times the
# stretched map's
size_scene 'box { min -2 -1 -1 max 2 1 1 surface s }' 'size 0.5 0.25' >"$T/sbox.scene"
size_scene 'box { min -2 -1 -1 max 2 1 1 surface s }' '' >"$T/ebox.scene"
if t_apply "$T/sbox.scene" -o "$T/sbox.exr" && t_apply "$T/ebox.scene" -o "$T/ebox.exr"; then
    read -r su _ _ < <(wraps "$T/sbox.exr" 0)
    read -r _ _ sf < <(wraps "$T/sbox.exr" 2)
    read -r _ sv _ < <(wraps "$T/sbox.exr" 1)
    read -r eu ev ef < <(wraps "$T/ebox.exr" 2)
    [ "$su $sv $eu $ev" = "7 7 0 0" ] &&
        ok "size: a 4 x 2 box face holds 8 x 8 maps of 0.5 x 0.25 (stretched: one)" ||
        notok "size on a box" "wraps across, up: $su $sv, stretched $eu $ev"
    awk -v a="$sf" -v b="$ef" 'BEGIN { exit !(b > 0 && a / b > 7.9 && a / b < 8.1) }' &&
        ok "size: the footprint follows the map's size (8 times, $sf against $ef)" ||
        notok "size: footprint" "$sf against $ef"
else
    notok "size on a box: renders"
fi
# spheres of radius 1 and 2 under maps of 1 x 1: the bigger one shows twice the maps
# around its equator (2 pi r of them) and down a meridian (pi r): 3.1 and 6.3 in view,
# less the wraps the grazing edges hide
for r in 1 2; do
    size_scene "sphere { centre 0 0 0 radius $r surface s }" 'size 1 1' >"$T/sph$r.scene"
    t_apply "$T/sph$r.scene" -o "$T/sph$r.exr" || notok "size on a sphere of radius $r: renders"
done
read -r w1 _ _ < <(wraps "$T/sph1.exr" 0)
read -r w2 _ _ < <(wraps "$T/sph2.exr" 0)
read -r _ v1 _ < <(wraps "$T/sph1.exr" 1)
read -r _ v2 _ < <(wraps "$T/sph2.exr" 1)
[ "${w1:-0}" -ge 2 ] && [ "${v1:-0}" -ge 2 ] && [ "$w2" -ge $((2 * w1)) ] &&
    [ "$v2" -ge $((2 * v1)) ] && [ "$w2" -le 7 ] && [ "$v2" -le 7 ] &&
    ok "size: a sphere twice as big shows twice the maps (u wraps $w1, $w2; v $v1, $v2)" ||
    notok "size on spheres" "u wraps $w1 $w2, v wraps $v1 $v2"
# a plane's natural mapping under size 2 3: u = fract(x / 2), v = fract(z / 3) of its own x, z
for k in uv:'rgb(u, v, 0)' xz:'rgb(0.5 + ox / 40, 0.5 + oz / 40, 0)'; do
    printf '%s\n' 'image 48 48' 'camera { eye 0 8 0 look 0 0 0 up 0 0 1 fov 90 }' \
        'ambient 1 1 1' 'texture n noise { }' \
        "surface s { Ka 1 Kd 1 apply n { size 2 3 Kd = ${k#*:} + 0 * f } }" \
        'plane { surface s }' >"$T/pl-${k%%:*}.scene"
    t_apply "$T/pl-${k%%:*}.scene" -o "$T/pl-${k%%:*}.pfm" || notok "size on a plane: renders"
done
got=$(py - "$T/pl-uv.pfm" "$T/pl-xz.pfm" <<'P'
import math, sys, pfm
(a, w, h), (b, _, _) = pfm.load(sys.argv[1]), pfm.load(sys.argv[2])
bad = 0
for i in range(w * h):
    x, z = (b[3 * i] - 0.5) * 40, (b[3 * i + 1] - 0.5) * 40
    for got, c, size in ((a[3 * i], x, 2), (a[3 * i + 1], z, 3)):
        want = c / size - math.floor(c / size)
        bad += min(want, 1 - want) > 1e-3 and abs(got - want) > 1e-3
print(w * h, bad)
P
)
[ "$got" = "2304 0" ] && ok "size: a plane repeats the map every 2 x 3 units of x and z" ||
    notok "size on a plane" "pixels, wrong: $got"
# a sized natural mapping is left out of the AVX-512 lanes (they map unsized): the packets
# and the vector paths give the pixel-by-pixel render's bytes, a bumped map on a sphere
awk 'BEGIN { print "P3 30 17 255"; for (y = 0; y < 17; y++) for (x = 0; x < 30; x++)
    print (x * 8) % 256, (y * 15) % 256, ((x + y) * 37) % 256 }' >"$T/colour.ppm"
cat >"$T/lanes.scene" <<S
image 120 96
camera { eye 0 6 0 look 0 0 0 up 0 0 1 fov 20 }
light point { position -3 8 -4 }
texture colour file "$T/colour.ppm"
surface sized { Kd 0.6 0.6 0.6 apply colour { mapping natural size 0.4 0.3 Kd = f bump = 0.3 } }
sphere { centre 0 0.5 0 radius 0.9 surface sized }
S
same_paths size "$T/lanes.scene"
# bad words: one line naming the input and the valid range, exit 2, no output
printf 'texture n noise { }\nsurface s { apply n { size 0 1 Kd = f } }\n' >"$T/bad1.scene"
check_fails "size 0 1 is refused" 2 t_apply "$T/bad1.scene" -o "$T/bad1.png"
grep -q "size needs W > 0 and H > 0 (got 0 1)" "$T/.err" && [ ! -e "$T/bad1.png" ] &&
    ok "size 0 1: says W and H must be > 0" || notok "size 0 1: message" "$(cat "$T/.err")"
printf 'texture n noise { }\nsurface s { apply n { mapping planar size 1 1 Kd = f } }\n' >"$T/bad2.scene"
check_fails "size with a planar mapping is refused" 2 t_apply "$T/bad2.scene" -o "$T/bad2.png"

# ---- P as a target (table 4.1): the point moved along the normal ----
p_scene() { # APPLY-BLOCKS LIGHTS
    cat <<S
image 48 48
camera { eye 0 3 0 look 0 0 0 up 0 0 1 fov 100 }
$2
texture n noise { }
surface s { Ka 1 Kd 1 Ks 0 $1 }
plane { surface s }
S
}
# the textures after it are looked up at the moved point: y = 0.5 on the floor y = 0
p_scene 'apply n { P = 0.5 } apply n { mapping world Kd = 2 * y + 0 * f }' 'ambient 1 1 1' \
    >"$T/plook.scene"
if t_apply "$T/plook.scene" -o "$T/plook.exr"; then
    got=$(counts "$T/plook.exr" | awk '{ printf "%g:%s ", $1, $2 }')
    [ "$got" = "1:2304 " ] && ok "P = 0.5: the next texture looks up at y = 0.5 (every pixel)" ||
        notok "P: lookups at the moved point" "values $got"
else
    notok "P: lookups at the moved point: renders"
fi
# and the light is shaded there: a point light 1 above the floor's origin lights the hit r
# from it at cos = 1 / sqrt(1 + r^2), the point moved up 0.5 at 0.5 / sqrt(0.25 + r^2)
light='ambient 0 0 0 light point { position 0 1 0 }'
p_scene 'Ka 0' "$light" >"$T/pflat.scene"
p_scene 'Ka 0 apply n { P = 0.5 }' "$light" >"$T/pmove.scene"
if t_apply "$T/pflat.scene" -o "$T/pflat.pfm" && t_apply "$T/pmove.scene" -o "$T/pmove.pfm"; then
    py - "$T/pflat.pfm" "$T/pmove.pfm" <<'P' >"$T/pcheck" 2>&1
import math, sys, pfm
(a, _, _), (b, _, _) = pfm.load(sys.argv[1]), pfm.load(sys.argv[2])
n = bad = 0
for i in range(0, len(a), 3):
    if not a[i] > 0.05: continue
    r2 = 1 / (a[i] * a[i]) - 1
    want = 0.5 / math.sqrt(0.25 + r2)
    n += 1; bad += abs(b[i] - want) > 1e-4
print(n, bad)
P
    read -r n bad <"$T/pcheck"
    [ "${n:-0}" -gt 2000 ] && [ "$bad" = 0 ] &&
        ok "P = 0.5: a point light shades the moved point ($n pixels)" ||
        notok "P: shading at the moved point" "$(cat "$T/pcheck")"
else
    notok "P: shading: renders"
fi
# a textured P on a sphere over a floor, shadows and all: packets and the vector paths give
# the pixel-by-pixel render's bytes
cat >"$T/ppk.scene" <<S
image 64 48
camera { eye 0 2 -4 look 0 0.5 0 fov 60 }
light point { position -2 4 -3 }
texture n noise { solid frequency 6 }
texture colour file "$T/colour.ppm"
surface s { Kd 0.8 0.6 0.4 Ks 0.3 apply n { mapping solid P = 0.05 * f bump = 0.3 }
    apply colour { Kd = f } }
surface floor { Kd 0.7 0.7 0.7 apply colour { mapping planar P = 0.2 * f Kd = f } }
sphere { centre 0 0.6 0 radius 0.6 surface s }
plane { surface floor }
S
same_paths P "$T/ppk.scene"

# ---- the infinite cone (inf_cone, thesis 5.3.1's inf_cone_map) ----
# a double cone of apex 0 along y, radius 0.5 |y|, seen from the side: every hit lies on
# x^2 + z^2 = (y / 2)^2, its normal along (x, -y / 4, z), v = fract(-y), and both nappes
# reach the top and bottom rows (no caps, no bounds)
ic_scene() { # KD
    cat <<S
image 48 64
camera { eye 0 0 -12 look 0 0 0 fov 40 }
ambient 1 1 1
texture n noise { }
surface s { Ka 1 Kd 1 apply n { Kd = $1 + 0 * f } }
inf_cone { base 0 0 0 top 0 1 0 radius1 0 radius2 0.5 surface s }
S
}
ic_scene 'rgb(0.5 + 0.5 * nx, 0.5 + 0.5 * ny, 0.5 + 0.5 * nz)' >"$T/icn.scene"
ic_scene 'rgb(0.5 + ox / 20, 0.5 + oy / 20, 0.5 + oz / 20)' >"$T/icp.scene"
ic_scene 'rgb(v, u, 0.5)' >"$T/icv.scene"
if t_apply "$T/icn.scene" -o "$T/icn.pfm" && t_apply "$T/icp.scene" -o "$T/icp.pfm" &&
    t_apply "$T/icv.scene" -o "$T/icv.pfm"; then
    py - "$T/icn.pfm" "$T/icp.pfm" "$T/icv.pfm" <<'P' >"$T/iccheck" 2>&1
import math, sys, pfm
(N, w, h), (Pp, _, _), (V, _, _) = (pfm.load(f) for f in sys.argv[1:4])
n = bad = up = down = 0
rows = set()
for i in range(w * h):
    if Pp[3 * i + 2] == 0: continue  # the sky
    x, y, z = ((Pp[3 * i + k] - 0.5) * 20 for k in range(3))
    nx, ny, nz = (2 * N[3 * i + k] - 1 for k in range(3))
    m = math.sqrt(x * x + y * y / 16 + z * z)
    g = (x / m, -y / 16 / m * 4, z / m)
    dot = nx * g[0] + ny * g[1] + nz * g[2]
    v = -y - math.floor(-y)
    n += 1
    rows.add(i // w)
    up += y > 0.5; down += y < -0.5
    if abs(math.hypot(x, z) - abs(y) / 2) > 2e-3 or abs(abs(dot) - 1) > 1e-3 or \
       (min(v, 1 - v) > 2e-3 and abs(V[3 * i] - v) > 2e-3):
        bad += 1
print(n, bad, up, down, int(0 in rows and h - 1 in rows))
P
    read -r n bad up down ends <"$T/iccheck"
    [ "${n:-0}" -gt 300 ] && [ "$bad" = 0 ] && [ "$up" -gt 100 ] && [ "$down" -gt 100 ] &&
        [ "$ends" = 1 ] &&
        ok "inf_cone: hits on the double cone, its normal and v, both nappes unbounded ($n)" ||
        notok "inf_cone: surface, normal, v" "$(cat "$T/iccheck")"
else
    notok "inf_cone: renders"
fi
# CSG: a box less an infinite cylinder along z is a box with a hole through it
cat >"$T/ichole.scene" <<S
image 41 41
camera { eye 0 0 -10 look 0 0 0 fov 20 }
ambient 1 1 1
surface s { Ka 1 Kd 1 1 1 }
difference { box { min -1 -1 -1 max 1 1 1 }
             inf_cone { base 0 0 0 top 0 0 1 radius1 0.5 radius2 0.5 } surface s }
S
if t_apply "$T/ichole.scene" -o "$T/ichole.pfm"; then
    got=$(py -c '
import sys, pfm
a, w, h = pfm.load(sys.argv[1])
print(*(pfm.px(a, w, h, x, y) for x, y in ((20, 20), (23, 20), (32, 20), (20, 8))))' \
        "$T/ichole.pfm")
    [ "$got" = "0.0 0.0 1.0 1.0" ] &&
        ok "inf_cone in CSG: a box less an infinite cylinder has a hole through it" ||
        notok "inf_cone in CSG" "centre, in the hole, the box, the box: $got"
else
    notok "inf_cone in CSG: renders"
fi
printf 'inf_cone { radius1 0 radius2 0 }\n' >"$T/bad3.scene"
check_fails "inf_cone with both radii 0 is refused" 2 t_apply "$T/bad3.scene" -o "$T/bad3.png"
