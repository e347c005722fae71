#!/usr/bin/env bash
# t_apply's texture model: quantities of the hit and functions in application functions
# (composition at application time), palettes in scenes, the wood primitive, bricks per
# cell, solid holes and colour variation, and the bugs fixed with them.
. "$(dirname "$0")/../lib.sh"

# pixels MAP: "x y r g b" per pixel, top row first (through PFM).
pixels() { # (its own PFM: two may run at once in a paste)
    local pfm
    pfm=$(mktemp "$T/px.XXXXXX").pfm
    t_convert -o "$pfm" "$1" && python3 - "$pfm" <<'P'
import array, sys
d = open(sys.argv[1], 'rb').read()
kind, size, scale, rest = d.split(b'\n', 3)
w, h = map(int, size.split())
nc = 3 if kind == b'PF' else 1
a = array.array('f'); a.frombytes(rest[:w * h * nc * 4])
if float(scale) > 0: a.byteswap()
for y in range(h):
    row = h - 1 - y
    for x in range(w):
        v = a[(row * w + x) * nc:(row * w + x + 1) * nc]
        print(x, y, *(list(v) * 3)[:3])
P
}

# ---- selection by distance: a floor receding from a camera 1 above it ----
floor_scene() { # EXPR: the floor's Kd
    cat <<S
image 64 48
camera { eye 0 1 0 look 0 1 10 fov 60 }
ambient 1 1 1
texture n noise { frequency 4 }
surface floor { Ka 1 Kd 1 apply n { mapping world Kd = $1 } }
plane { normal 0 1 0 distance 0 surface floor }
S
}
# the path length to the floor at pixel (x, y), from the camera's geometry (render.c)
dist_check() { # MAP WHAT: compare every floor pixel with WHAT(dist) in python
    pixels "$1" | python3 -c '
import math, sys
w, h, fov = 64, 48, 60
sx = math.tan(fov * math.pi / 360); sy = sx * h / w
kx, ky = 2 * sx / w, 2 * sy / h
def smooth(a, b, x):
    s = min(max((x - a) / (b - a), 0), 1); return s * s * (3 - 2 * s)
bad = n = 0
for line in sys.stdin:
    x, y, r, g, b = line.split(); x, y = int(x), int(y); r, g, b = map(float, (r, g, b))
    a = (x + 0.5) * kx - sx; bb = sy - (y + 0.5) * ky
    l = math.sqrt(1 + a * a + bb * bb)
    if bb >= -1e-9: continue          # the sky
    d = -1 / (bb / l)                   # 1 + t dy = 0
    if abs(d - 5) < 0.05 or abs(d - 4) < 0.05 or abs(d - 6) < 0.05: continue  # at the edges
    want = eval(sys.argv[1]); n += 1
    if abs(r - want[0]) > 2e-4 or abs(b - want[2]) > 2e-4: bad += 1
print(n, bad)' "$2"
}
floor_scene 'if(dist < 5, 1 0 0, 0 0 1)' >"$T/step.scene"
t_apply "$T/step.scene" -o "$T/step.exr"
read -r n bad < <(dist_check "$T/step.exr" '(1, 0, 0) if d < 5 else (0, 0, 1)')
[ "$n" -gt 500 ] && [ "$bad" = 0 ] && ok "selection by distance: map A before 5, map B after ($n pixels)" ||
    notok "selection by distance" "$bad of $n pixels wrong"
floor_scene 'mix(1 0 0, 0 0 1, smoothstep(4, 6, dist))' >"$T/blend.scene"
t_apply "$T/blend.scene" -o "$T/blend.exr"
read -r n bad < <(dist_check "$T/blend.exr" '(1 - smooth(4, 6, d), 0, smooth(4, 6, d))')
[ "$n" -gt 500 ] && [ "$bad" = 0 ] && ok "a smoothstep blend over distance 4..6 ($n pixels)" ||
    notok "smoothstep blend by distance" "$bad of $n pixels off"
# every quantity and function parses and renders; results stay in range
floor_scene '0.5 + 0*(footprint + lod + ndotv + depth + x + y + z + ox + oy + oz + u + v + w + nx + ny + nz + region) + 0*(pow(2, 3) + sin(1) + cos(1) + floor(1.5) + fract(1.5) + step(0.5, f) + clamp(f, 0, 1) + min(f, 1) + max(f, 0) + abs(-f)) + 0*(f < 1) + 0*(f > 1) + 0*(f <= 1) + 0*(f >= 1) + 0*(f == 1) + 0*(f != 1)' \
    >"$T/all.scene"
t_apply "$T/all.scene" -o "$T/all.exr" && approx "$(info_json "$T/all.exr" stats 1 max)" 0.5 1e-6 &&
    ok "every quantity, function and comparison in one expression" || notok "all quantities and functions"
floor_scene 'if(ndotv > 0.3, 1, 0) + 0*f' >"$T/ndotv.scene"
t_apply "$T/ndotv.scene" -o "$T/ndotv.exr"
# ndotv = |dy| / |d| on the floor: the near rows see it steeply, the far rows at a grazing angle
far=$(pixels "$T/ndotv.exr" | awk '$1 == 32 && $2 == 25 { print $3 }')
near=$(pixels "$T/ndotv.exr" | awk '$1 == 32 && $2 == 47 { print $3 }')
approx "$near" 1 0 && approx "$far" 0 0 && ok "ndotv: steep near rows, grazing far rows" ||
    notok "ndotv" "near $near far $far"

# ---- palettes in scenes equal t_palette on the same map ----
t_noise -s 64 -S 1 -o "$T/n.exr"
t_palette marble "$T/n.exr" -o "$T/n_marble.exr"
plane_scene() { # TEXTURE-LINE: a plane facing the camera, lit by the ambient light only
    cat <<S
image 48 48
camera { eye 0 0 -3 look 0 0 0 fov 50 }
ambient 1 1 1
$1
surface s { Ka 1 Kd 1 apply t { mapping planar Kd = f } }
box { min -1 -1 0 max 1 1 0.1 surface s }
S
}
plane_scene "texture t file \"$T/n.exr\" palette marble" >"$T/pal.scene"
plane_scene "texture t file \"$T/n_marble.exr\"" >"$T/pal_ref.scene"
t_apply "$T/pal.scene" -o "$T/pal.exr" && t_apply "$T/pal_ref.scene" -o "$T/pal_ref.exr" &&
    same "a map file through 'palette marble' equals t_palette marble of it" "$T/pal.exr" "$T/pal_ref.exr" 1e-6
plane_scene "texture t noise { size 64 seed 1 palette marble }" >"$T/palp.scene"
t_apply "$T/palp.scene" -o "$T/palp.exr" &&
    same "a sampled primitive through 'palette marble' equals t_noise | t_palette marble" \
        "$T/palp.exr" "$T/pal_ref.exr" 1e-6
t_checker -s 64 --palette brick -o "$T/ck.exr"
plane_scene "texture t file \"$T/ck.exr\"" >"$T/ck_ref.scene"
plane_scene "texture t checker { size 64 palette brick }" >"$T/ck.scene"
t_apply "$T/ck.scene" -o "$T/ck1.exr" && t_apply "$T/ck_ref.scene" -o "$T/ck2.exr" &&
    same "a geometric primitive's palette equals t_checker --palette" "$T/ck1.exr" "$T/ck2.exr" 1e-6
plane_scene "texture t turbulence { palette fire }" >"$T/pt.scene"
sed 's/Kd = f/Kd = palette(fire, f)/; s/ { palette fire }/ { }/' "$T/pt.scene" >"$T/pe.scene"
t_apply "$T/pt.scene" -o "$T/pt.exr" && t_apply "$T/pe.scene" -o "$T/pe.exr" &&
    same "palette(NAME, f) in an expression equals the texture's palette at hit points" \
        "$T/pt.exr" "$T/pe.exr" 0
[ "$(info_json "$T/pt.exr" stats 0 max)" != "$(info_json "$T/pt.exr" stats 2 max)" ] &&
    ok "the palette colours the point primitive (red and blue differ)" || notok "palette colours"

# ---- bugs ----
# a geometric primitive without size is sampled (it gave the region id: white)
plane_scene "texture t checker { }" >"$T/cknosize.scene"
plane_scene "texture t checker { size 512 }" >"$T/ck512.scene"
t_apply "$T/cknosize.scene" -o "$T/cknosize.exr" && t_apply "$T/ck512.scene" -o "$T/ck512.exr" &&
    same "a checker without size is sampled at 512, as t_apply(5) says (not region ids)" \
        "$T/cknosize.exr" "$T/ck512.exr" 0
# solid mapping on a box: no untextured speckles where u or v is 0 on a face
cat >"$T/speck.scene" <<'S'
image 96 96
camera { eye 3 2.5 -4 look 0 0 0 fov 40 }
ambient 1 1 1
texture t turbulence { solid }
surface s { Ka 1 Kd 0 0 1 apply t { mapping solid Kd = 1 0 0 } }
box { min -1 -1 -1 max 1 1 1 surface s }
S
t_apply "$T/speck.scene" -o "$T/speck.exr"
[ "$(info_json "$T/speck.exr" stats 2 max)" = 0 ] && ok "solid mapping covers every face of a box" ||
    notok "solid mapping speckles" "blue max $(info_json "$T/speck.exr" stats 2 max)"

# ---- primitives ----
t_wood -s 64 --turbulence 0 --rings 5 -o "$T/wood.exr"
pixels "$T/wood.exr" | python3 -c '
import sys
v = {}
for l in sys.stdin:
    x, y, r, g, b = l.split(); v[int(x), int(y)] = float(r)
bad = sum(1 for (x, y) in v if abs(v[x, y] - v[63 - x, y]) > 1e-5 or abs(v[x, y] - v[y, x]) > 1e-5)
span = max(v.values()) - min(v.values())
sys.exit(0 if bad == 0 and span > 0.9 else 1)' &&
    ok "wood rings are concentric: the value depends on the distance to the axis" || notok "wood rings concentric"
t_wood -s 64 --tilt 90 --turbulence 0 --rings 5 -o "$T/plank.exr"
pixels "$T/plank.exr" | awk '{ v[$1] = v[$1] " " $3 } END { for (x in v) { n = split(v[x], a, " "); for (i = 2; i <= n; i++) if (a[i] != a[1]) bad++ } exit bad > 0 }' &&
    ok "wood at tilt 90: the grain runs down the map (columns constant)" || notok "wood plank"
sed 's/turbulence { solid }/wood { solid }/' "$T/speck.scene" >"$T/wood.scene"
check "a solid wood texture renders" t_apply "$T/wood.scene" -o "$T/woods.exr"
t_brick -s 256 --cells --nu 4 --nv 4 -o "$T/cells.exr"
# brick centres: upper courses at v = (j + 0.25) / 4, lower at (j + 0.75) / 4
pixels "$T/cells.exr" | python3 -c '
import sys
px = {}
for l in sys.stdin:
    x, y, r, g, b = l.split(); px[int(x), int(y)] = (r, g, b)
cols = {px[32 + 64 * i, 16 + 64 * j] for i in range(4) for j in range(4)}
mortar = px[0, 0]
sys.exit(0 if len(cols) >= 6 and mortar not in cols else 1)' &&
    ok "t_brick --cells: bricks differ in colour per brick, mortar apart" || notok "brick cells"
t_brick -s 64 --cells --ids -o "$T/ids.exr"
n=$(info_json "$T/ids.exr" stats 0 max); approx "$n" 33 8 && ok "brick cell ids lie in 2..2 nu nv + 1" || notok "brick ids" "max $n"
check_fails "--cells with too many repetitions" 2 t_brick --cells --nu 4096 --nv 4096 -s 8 -o "$T/x.exr"

# ---- bad scenes: one line with file:line:col, exit 2, no image ----
bad() {
    printf '%s\n' "$2" >"$T/bad.scene"
    check_fails "$1" 2 t_apply "$T/bad.scene" -o "$T/bad.png"
    [ -e "$T/bad.png" ] && notok "$1: no output file"
    grep -q "bad.scene:[0-9]*:[0-9]*:" "$T/.err" || notok "$1: file:line:col" "$(cat "$T/.err")"
}
bad "unknown quantity" 'texture t noise { } surface s { apply t { Kd = distance } }'
bad "unknown function" 'texture t noise { } surface s { apply t { Kd = sinh(f) } }'
bad "wrong argument count" 'texture t noise { } surface s { apply t { Kd = mix(f, 1) } }'
bad "palette without a value" 'texture t noise { } surface s { apply t { Kd = palette(fire) } }'
bad "unknown palette in an expression" 'texture t noise { } surface s { apply t { Kd = palette(nosuch, f) } }'
grep -q "known: .*marble" "$T/.err" && ok "an unknown palette's message lists the known ones" ||
    notok "unknown palette lists names" "$(cat "$T/.err")"
bad "unknown palette on a texture" 'texture t noise { palette nosuch }'
bad "palette on a colour map" "texture t file \"$T/ck.exr\" palette fire"

# ---- the shipped scenes that show it, as goldens ----
for sc in resolution sheen; do
    t_apply "${TEXTURA_TOP:-.}/patterns/$sc.scene" -s 80x48 --spp 1 -o "$T/$sc.exr" &&
        golden "patterns/$sc.scene golden" "$T/$sc.exr" "apply_$sc.exr" 1e-5
done

# ---- projections (thesis 5.2.1.3): checked through the quantities u v w and ox oy oz ----
# coords SURFACE-APPLY: render Kd = rgb(u, v, w) and Kd = the object point mapped to [0, 1]
# on a unit sphere, and print "u v w ox oy oz" per pixel of the sphere.
coords() {
    for kd in 'rgb(u, v, w)' 'rgb((ox + 1) / 2, (oy + 1) / 2, (oz + 1) / 2)'; do
        cat <<S
image 48 48
camera { eye 0.5 1 -4 look 0 0 0 fov 40 }
ambient 1 1 1
texture t noise { }
surface s { Ka 1 Kd 0 0 0 apply t { $1 Kd = $kd } }
sphere { radius 1 surface s }
S
    done >"$T/c.both"
    head -6 "$T/c.both" >"$T/c1.scene"; tail -6 "$T/c.both" >"$T/c2.scene"
    t_apply "$T/c1.scene" -o "$T/c1.exr" && t_apply "$T/c2.scene" -o "$T/c2.exr" &&
        paste -d' ' <(pixels "$T/c1.exr") <(pixels "$T/c2.exr") |
        awk '$8 + $9 + $10 > 0 { print $3, $4, $5, 2 * $8 - 1, 2 * $9 - 1, 2 * $10 - 1 }'
}
# check_coords NAME MAPPING PYTHON-EXPR-FOR-(U, V): over every sphere pixel, within 1e-4
check_coords() {
    local r
    r=$(coords "$2" | python3 -c '
import math, sys
def fract(x): return x - math.floor(x)
n = bad = 0
for l in sys.stdin:
    u, v, w, ox, oy, oz = map(float, l.split())
    eu, ev = eval(sys.argv[1]); n += 1
    du = min(abs(u - eu), 1 - abs(u - eu))   # wrapped at 0 = 1
    if du > 1e-4 or abs(v - ev) > 1e-4: bad += 1
print(n, bad)' "$3")
    set -- "$1" $r
    [ "$2" -gt 300 ] && [ "$3" = 0 ] && ok "$1 ($2 points)" || notok "$1" "$3 of $2 points off"
}
check_coords "planar along x: (u, v) = ((z + 1) / 2, (y + 1) / 2), constant along the axis" \
    'mapping planar axis 1 0 0' '((oz + 1) / 2, (oy + 1) / 2)'
check_coords "planar along y, the default: (u, v) = ((x + 1) / 2, (z + 1) / 2)" \
    'mapping planar' '((ox + 1) / 2, (oz + 1) / 2)'
check_coords "translate moves the projected map with the object" \
    'mapping planar translate 0.2 0 0' '(max(0, (ox - 0.2 + 1) / 2), (oz + 1) / 2)'
check_coords "rotate 0 90 0 turns the projected map a quarter about y" \
    'mapping planar rotate 0 90 0' '((1 - oz) / 2, (ox + 1) / 2)'
check_coords "the wavy path follows its sine: u + A sin(2 pi y / L)" \
    'mapping wavy wave 0.1 0.5' 'fract((ox + 1) / 2 + 0.1 * math.sin(2 * math.pi * oy / 0.5)), (oz + 1) / 2'
check_coords "cross: the x-y map at (u, v), the y-z map at (w, v)" \
    'mapping cross cross t' '((ox + 1) / 2, (1 - oy) / 2)'

# On a cylinder's side the cylinder projection is its natural mapping (u around the axis,
# v down it), and its derivatives are too: the same footprints (mip levels) and bump tilts,
# so the same bytes where only the side shows (a tall cylinder seen from mid-height)
t_noise -s 64 -f 6 -o "$T/grain.exr"
for m in natural cylinder; do
    cat >"$T/side-$m.scene" <<S
image 64 48
camera { eye 0 0 -6 look 0 0 0 fov 35 }
light point { position -3 2 -5 }
texture g file "$T/grain.exr"
surface s { Kd 0.9 0.9 0.9 apply g { mapping $m repeat 3 2 Kd = f bump = 0.5 } }
cylinder { base 0 -20 0 top 0 20 0 radius 1 surface s rotate 0 25 0 }
S
    t_apply "$T/side-$m.scene" -q -o "$T/side-$m.pfm" || notok "cylinder side ($m) renders"
done
cmp -s "$T/side-natural.pfm" "$T/side-cylinder.pfm" &&
    ok "cylinder projection on a cylinder's side: the natural mapping's bytes (footprints, bump)" ||
    notok "cylinder projection against the natural mapping on a side" \
        "$(maxdiff "$T/side-natural.pfm" "$T/side-cylinder.pfm")"

# the two-plane product equals the product of the two maps at the points they map to
t_checker -s 64 --nu 2 --nv 2 --ids -o "$T/ca.exr"
t_stripe -s 64 --ids -o "$T/cb.exr"
cat >"$T/cross.scene" <<S
image 48 48
camera { eye 0.5 1 -4 look 0 0 0 fov 40 }
ambient 1 1 1
filter off
texture a file "$T/ca.exr"
texture b file "$T/cb.exr"
surface s { Ka 1 Kd 0 0 0 apply a { mapping cross cross b combine product Kd = f / 4 } }
sphere { radius 1 surface s }
S
sed 's|Kd = f / 4|Kd = rgb(u, v, w)|' "$T/cross.scene" >"$T/crossuv.scene"
t_apply "$T/cross.scene" -o "$T/cross.exr" && t_apply "$T/crossuv.scene" -o "$T/crossuv.exr"
t_convert -o "$T/ca.pfm" "$T/ca.exr"; t_convert -o "$T/cb.pfm" "$T/cb.exr"
r=$(paste -d' ' <(pixels "$T/cross.exr") <(pixels "$T/crossuv.exr") | python3 -c '
import array, sys
def load(p):
    d = open(p, "rb").read(); k, s, sc, rest = d.split(b"\n", 3)
    w, h = map(int, s.split()); a = array.array("f"); a.frombytes(rest[:w * h * 4])
    return w, h, a
A, B = load(sys.argv[1]), load(sys.argv[2])
def at(m, u, v):  # the region id of the texel (u, v) falls in (rows bottom-up in PFM)
    w, h, a = m; x = min(int(u * w), w - 1); y = min(int(v * h), h - 1)
    return a[(h - 1 - y) * w + x]
n = bad = 0
for l in sys.stdin:
    f = l.split(); c = float(f[2]); u, v, w = map(float, f[7:10])
    if u + v + w == 0: continue
    near = lambda t: abs(t * 64 - round(t * 64)) < 0.01   # on a texel edge: either id
    if near(u) or near(v) or near(w): continue
    n += 1
    if abs(c - at(A, u, v) * at(B, w, v) / 4) > 1e-5: bad += 1
print(n, bad)' "$T/ca.pfm" "$T/cb.pfm")
set -- $r
[ "$1" -gt 200 ] && [ "$2" = 0 ] && ok "cross product equals the two maps' product at sampled points ($1)" ||
    notok "cross product" "$2 of $1 off"

bad "projection axis of length 0" 'texture t noise { } surface s { apply t { mapping planar axis 0 0 0 Kd = f } }'
bad "wavy amplitude NaN" 'texture t noise { } surface s { apply t { mapping wavy wave nan 1 Kd = f } }'
bad "wavy wavelength 0" 'texture t noise { } surface s { apply t { mapping wavy wave 0.1 0 Kd = f } }'
bad "cross without its second map" 'texture t noise { } surface s { apply t { mapping cross Kd = f } }'
bad "translate with mapping natural" 'texture t noise { } surface s { apply t { translate 1 0 0 Kd = f } }'

# ---- the environment (Blinn-Newell reflection mapping) ----
# a ramp: R = u, G = v at texel centres, so a direction's colour is its (u, v)
python3 - "$T/ramp.pfm" <<'P'
import struct, sys
w, h = 64, 32
with open(sys.argv[1], 'wb') as f:
    f.write(b'PF\n%d %d\n-1.0\n' % (w, h))
    for row in range(h):          # bottom row first
        y = h - 1 - row
        for x in range(w):
            f.write(struct.pack('<3f', (x + 0.5) / w, (y + 0.5) / h, 0.25))
P
t_op mul "$T/ramp.pfm" 0 | t_op add - 0.3 -o "$T/grey.exr"   # constant 0.3
cat >"$T/mirror.scene" <<S
image 32 32
camera { eye 0 0 -3 look 0 0 0 fov 60 }
ambient 0 0 0
environment "$T/grey.exr" { intensity 2 }
surface mirror { Ka 0 Kd 0 Ks 0 Kr 1 }
sphere { radius 1 surface mirror }
S
t_apply "$T/mirror.scene" -o "$T/mirror.exr" &&
    approx "$(info_json "$T/mirror.exr" stats 0 min)" 0.6 1e-6 &&
    approx "$(info_json "$T/mirror.exr" stats 2 max)" 0.6 1e-6 &&
    ok "a mirror sphere (Kr 1) in a constant environment c shows c, as the background does" ||
    notok "mirror in a constant environment" "$(t_info "$T/mirror.exr" | head -3)"
# directions: a camera at the origin looking along d sees the texel of d at its centre
r=""
for d in "0 0 1" "1 0 0" "0.2 0 -1" "-1 0 0.0001" "1 1 1" "0.3 -0.7 0.2"; do
    printf 'image 3 3\ncamera { eye 0 0 0 look %s fov 1 }\nfilter off\nenvironment "%s"\n' \
        "$d" "$T/ramp.pfm" >"$T/env.scene"
    t_apply "$T/env.scene" -o "$T/env.exr" 2>/dev/null || r="$r fail"
    got=$(pixels "$T/env.exr" | awk '$1 == 1 && $2 == 1 { print $3, $4 }')
    r="$r $(python3 -c '
import math, sys
x, y, z = map(float, sys.argv[1].split()); l = math.sqrt(x*x + y*y + z*z)
u = 0.5 + math.atan2(x, z) / (2 * math.pi); v = math.acos(y / l) / math.pi
gu, gv = map(float, sys.argv[2].split())
print("ok" if abs(gu - u) < 2e-3 and abs(gv - v) < 2e-3 else "bad(%s:%g,%g/%g,%g)" % (sys.argv[1], gu, gv, u, v))' "$d" "$got")"
done
[ "$(tr ' ' '\n' <<<"$r" | grep -vc '^ok$\|^$')" = 0 ] &&
    ok "a lat-long map's texels appear in the directions that map to them" || notok "environment directions" "$r"
printf 'image 3 3\ncamera { eye 0 0 0 look 0 0 1 fov 1 }\nfilter off\nenvironment "%s" { rotate 0 90 0 }\n' \
    "$T/ramp.pfm" >"$T/envr.scene"
t_apply "$T/envr.scene" -o "$T/envr.exr" 2>/dev/null
u=$(pixels "$T/envr.exr" | awk '$1 == 1 && $2 == 1 { print $3 }')
approx "$u" 0.25 2e-3 && ok "rotate 0 90 0 turns the environment a quarter: +z sees u = 0.25" ||
    notok "environment rotate" "u $u"
printf 'environment "/nonexistent/sky.exr"\n' >"$T/noenv.scene"
check_fails "a missing environment map: exit 1" 1 t_apply "$T/noenv.scene" -o "$T/bad.png"
grep -q "noenv.scene:1:13: cannot read the environment map" "$T/.err" && [ ! -e "$T/bad.png" ] &&
    ok "a missing environment map: file:line:col, no image" || notok "missing environment" "$(cat "$T/.err")"
t_fractal --mode fbm -s 128x64 -f 6 | t_palette sky |
    t_apply "${TEXTURA_TOP:-.}/patterns/mirror_ball.scene" -s 80x48 --spp 1 -o "$T/mirror_ball.exr" &&
    golden "patterns/mirror_ball.scene golden" "$T/mirror_ball.exr" apply_mirror_ball.exr 1e-5

# ---- every shading parameter a target ----
# a floor seen from above under a point light: the highlight's spread, with m from a map
ct_scene() { # M-EXPR
    cat <<S
image 64 64
camera { eye 0 4 -0.001 look 0 0 0 fov 60 }
ambient 0 0 0
light point { position 0 3 0 intensity 3 }
texture half file "$T/half.exr"
surface s { model cook-torrance Kd 0 0 0 ior 1.5 specular 1 facets beckmann 0.1
    apply half { mapping planar Ka = 0 $1 } }
plane { normal 0 1 0 distance 0 surface s }
S
}
t_op mul "$T/ramp.pfm" 0 | t_op add - 1 -o "$T/half.exr"
ct_scene "" >"$T/ct0.scene"; ct_scene "m = 0.1 + 0.3 * f" >"$T/ct1.scene"
t_apply "$T/ct0.scene" -o "$T/ct0.exr" && t_apply "$T/ct1.scene" -o "$T/ct1.exr"
# light reaching pixels away from the highlight's centre: a rougher surface spreads it
edge0=$(pixels "$T/ct0.exr" | awk '$1 == 32 && $2 == 4 { print $3 }')
edge1=$(pixels "$T/ct1.exr" | awk '$1 == 32 && $2 == 4 { print $3 }')
awk -v a="$edge0" -v b="$edge1" 'BEGIN { exit !(b > 2 * a && b > 0) }' &&
    ok "a Cook-Torrance roughness map (m = 0.1 + 0.3 f) widens the highlight where f is large" ||
    notok "roughness map widens the highlight" "edge $edge0 -> $edge1"
ct_scene "s = 0.5 * f" >"$T/cts.scene"
t_apply "$T/cts.scene" -o "$T/cts.exr"
c0=$(pixels "$T/ct0.exr" | awk '$1 == 32 && $2 == 32 { print $3 }')
c1=$(pixels "$T/cts.exr" | awk '$1 == 32 && $2 == 32 { print $3 }')
awk -v c="$c0" "BEGIN { exit !(c > 0.01) }" && approx "$c1" "$(awk -v c="$c0" "BEGIN { print c / 2 }")" 1e-4 &&
    ok "a specular-fraction map (s = 0.5 f) halves the highlight" || notok "s map" "$c0 -> $c1"
# a normal map of the flat normal changes nothing; a tilted one moves the shading
t_op mul "$T/ramp.pfm" 0 | t_op add - '0.5,0.5,1' -o "$T/flat.exr" 2>/dev/null ||
    python3 -c '
import struct, sys
with open(sys.argv[1], "wb") as f:
    f.write(b"PF\n8 8\n-1.0\n"); f.write(struct.pack("<3f", 0.5, 0.5, 1.0) * 64)' "$T/flat.pfm"
[ -e "$T/flat.exr" ] || t_convert "$T/flat.pfm" -o "$T/flat.exr"
nmap_scene() { # TEXTURE-FILE EXPR
    cat <<S
image 48 48
camera { eye 0 1.5 -3 look 0 0 0 fov 50 }
light point { position 2 3 -2 intensity 1.5 }
texture nm file "$1"
surface s { Kd 0.7 Ks 0.5 n 30 $2 }
sphere { radius 1 surface s }
S
}
nmap_scene "$T/flat.exr" "" >"$T/nm0.scene"
nmap_scene "$T/flat.exr" "apply nm { mapping planar normal = f }" >"$T/nm1.scene"
t_apply "$T/nm0.scene" -o "$T/nm0.exr" && t_apply "$T/nm1.scene" -o "$T/nm1.exr" &&
    same "a normal map of the flat normal changes nothing" "$T/nm0.exr" "$T/nm1.exr" 0
t_d_noise --normal --strength 3 -f 8 -s 128 -o "$T/dn.exr"
nmap_scene "$T/dn.exr" "apply nm { mapping sphere normal = f }" >"$T/nm2.scene"
t_apply "$T/nm2.scene" -o "$T/nm2.exr"
d=$(maxdiff "$T/nm0.exr" "$T/nm2.exr")
awk -v d="$d" 'BEGIN { exit !(d > 0.05) }' && ok "t_d_noise --normal as a normal map changes the shading" ||
    notok "normal map from t_d_noise" "max diff $d"
t_d_noise -f 8 -s 128 -o "$T/grad.exr"
nmap_scene "$T/grad.exr" "apply nm { mapping sphere gradient = 8 * f }" >"$T/gr.scene"
t_apply "$T/gr.scene" -o "$T/gr.exr"
d=$(maxdiff "$T/nm0.exr" "$T/gr.exr")
awk -v d="$d" 'BEGIN { exit !(d > 0.02) }' && ok "t_d_noise's gradient as a bump source changes the shading" ||
    notok "gradient bump" "max diff $d"
nmap_scene "$T/grad.exr" "apply nm { mapping sphere gradient = 0 * f }" >"$T/gr0.scene"
t_apply "$T/gr0.scene" -o "$T/gr0.exr" && same "a zero gradient changes nothing" "$T/nm0.exr" "$T/gr0.exr" 0
# two surfaces blended by a map: w = 0 is the first, w = 1 the second, w = 1/2 their mean
blend_scene() { # W-EXPR
    cat <<S
image 48 48
camera { eye 0 1.5 -3 look 0 0 0 fov 50 }
light point { position 2 3 -2 intensity 1.5 }
texture half file "$T/half.exr"
surface rust { Kd 0.5 0.2 0.05 Ks 0.05 n 5 }
surface steel { Kd 0.3 0.3 0.32 Ks 0.8 n 80 blend rust apply half { mapping sphere blend = $1 } }
surface rustonly { Kd 0.5 0.2 0.05 Ks 0.05 n 5 }
sphere { radius 1 surface SURF }
S
}
blend_scene "0 * f" | sed 's/SURF/steel/' >"$T/b0.scene"
blend_scene "f" | sed 's/SURF/steel/' >"$T/b1.scene"
blend_scene "0.5 * f" | sed 's/SURF/steel/' >"$T/bh.scene"
blend_scene "0 * f" | sed 's/SURF/rustonly/' >"$T/br.scene"
sed 's/ blend rust apply half { mapping sphere blend = 0 \* f }//' "$T/b0.scene" >"$T/bs.scene"
for b in b0 b1 bh br bs; do t_apply "$T/$b.scene" -o "$T/$b.exr"; done
same "blend = 0 shades the first surface alone" "$T/b0.exr" "$T/bs.exr" 0
same "blend = 1 shades the blended surface" "$T/b1.exr" "$T/br.exr" 1e-6
t_op add "$T/bs.exr" "$T/br.exr" | t_op mul - 0.5 -o "$T/bmean.exr"
same "blend = 1/2 is the mean of the two surfaces' light" "$T/bh.exr" "$T/bmean.exr" 1e-5

bad "a normal map of 1 channel" "texture g file \"$T/grad.exr\" surface s { apply g { normal = f } }"
t_noise -s 8 -o "$T/one.exr"
bad "a normal map of 1 channel (a map)" "texture g file \"$T/one.exr\" surface s { apply g { normal = f } }"
bad "blend naming an unknown surface" 'texture t noise { } surface s { blend nosuch apply t { blend = f } }'
bad "blend = h without blend SURFACE" 'texture t noise { } surface s { apply t { blend = f } }'
bad "m on a Phong surface" 'texture t noise { } surface s { apply t { m = f } }'
