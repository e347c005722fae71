#!/usr/bin/env bash
# Solid textures on their lattice's faces (issue 59, items 7 and 8): a surface at a whole
# coordinate of a solid texture's cells (the floor y = 0 under the world mapping, a box's
# faces under the solid mapping, a cylinder's caps) lies in one cell, as POV-Ray's
# tolerance makes it (prim/cell.h): no salt-and-pepper pixels where the hits' rounding put
# neighbours either side of the face.  And solid holes reach the cells' faces, so that a
# box's face on one keeps its holes.
. "$(dirname "$0")/../lib.sh"

# speckles MAP [ROWS]: the pixels (of the bottom ROWS rows, default all) that differ by over
# 0.1 from each of their four neighbours while those agree within 0.02: a pixel the field's
# cell flipped alone, which no edge or corner of a cell a few pixels wide makes.
speckles() {
    local pfm=$T/sp.$$.pfm
    t_convert -o "$pfm" "$1" && python3 - "$pfm" "${2:-0}" <<'P'
import array, sys
d = open(sys.argv[1], 'rb').read()
kind, size, scale, rest = d.split(b'\n', 3)
w, h = map(int, size.split()); nc = 3 if kind == b'PF' else 1
a = array.array('f'); a.frombytes(rest[:w * h * nc * 4])
if float(scale) > 0: a.byteswap()
px = lambda x, y: a[((h - 1 - y) * w + x) * nc]   # PFM rows run bottom up
rows = int(sys.argv[2]) or h
n = 0
for y in range(max(1, h - rows), h - 1):
    for x in range(1, w - 1):
        p, q = px(x, y), (px(x - 1, y), px(x + 1, y), px(x, y - 1), px(x, y + 1))
        if min(abs(p - r) for r in q) > 0.1 and max(q) - min(q) < 0.02:
            n += 1
print(n)
P
}

scene() { # TEXTURE MAPPING OBJECT KD: a 96x72 view of OBJECT lit by ambient light alone; under
    # the world mapping a unit of the field is 4 (the faces at whole coordinates lie on its
    # cells' faces still)
    cat <<S
image 96 72
camera { eye 0.35 2.2 -4.2 look 0 0.2 0 fov 50 }
ambient 1 1 1
texture t $1
surface s { Ka 1 Kd 0 0 0 apply t { mapping $2 scale 0.25 Kd = $4 } }
$3
S
}

# ---- the issue's floor: a checker at y = 0 under the world mapping, parity checked ----
scene "checker { solid nu 1 nv 1 nw 1 }" world "plane { normal 0 1 0 distance 0 surface s }" "f - 1" \
    >"$T/floor.scene"
t_apply "$T/floor.scene" -o "$T/floor.exr"
n=$(speckles "$T/floor.exr" 36)
[ "$n" = 0 ] && ok "a solid checker floor at y = 0: no pixel differs from both neighbours' parity" ||
    notok "checker floor at y = 0 speckles" "$n pixels"

# ---- every solid primitive of the registry on faces at whole coordinates ----
# Under the world mapping, each object renders as it does moved a little into the cells
# above its faces (x + d, -y + d, z + d: the mapping's w is -y), d = 1e-7 (4e-7 of a
# cell of 1/4 unit, far above the tolerance, far below a pixel): a face that lay in either
# cell at random differs from it.  Pixels over 0.02 apart, of 96x72, are counted.
objects=("plane { normal 0 1 0 distance 0 surface s"
    "box { min -1 0 -1 max 1 1 1 surface s"
    "cylinder { base 0 0 0 top 0 1 0 radius 1.2 surface s")
prims=$(sed -n 's/^TEX_PRIMITIVE(\(.*\))$/\1/p' "${TEXTURA_TOP:-.}/libtex/prim/primitives.def")
[ -n "$prims" ] || notok "the registry lists primitives"
solid=0 bad=""
for p in $prims; do
    scene "$p { solid }" world "plane { normal 0 1 0 distance 0 surface s }" "0.3 * f" \
        >"$T/probe.scene"
    t_apply "$T/probe.scene" -o "$T/probe.exr" 2>"$T/probe.err" || {
        grep -q "no solid (3D) form" "$T/probe.err" || bad="$bad $p(renders: $(head -c 100 "$T/probe.err"))"
        continue
    }
    solid=$((solid + 1))
    for o in "${objects[@]}"; do
        scene "$p { solid }" world "$o }" "0.3 * f" >"$T/on.scene"
        scene "$p { solid }" world "$o translate 1e-7 -1e-7 1e-7 }" "0.3 * f" >"$T/off.scene"
        t_apply "$T/on.scene" -o "$T/on.exr" && t_apply "$T/off.scene" -o "$T/off.exr" ||
            { bad="$bad $p(${o%% *}: fails)"; continue; }
        n=$(t_op sub "$T/on.exr" "$T/off.exr" | t_op abs - | t_op threshold -t 0.02 - | t_info --json - |
            awk '/"channel"/ { sub(/.*"mean": /, ""); sub(/[,}].*/, ""); print $0 * 96 * 72; exit }')
        [ "$n" = 0 ] || bad="$bad $p(${o%% *}: $n)"
    done
done
[ "$solid" -ge 10 ] && [ -z "$bad" ] &&
    ok "$solid solid primitives on the plane y = 0, a box's faces and a cylinder's caps: in one cell" ||
    notok "solid primitives speckle on faces at whole coordinates" "$solid solid; bad:${bad:0:400}"

# under the solid mapping (a box's faces at 0 and 1 of its box) and the box projection
for m in solid box; do
    scene "checker { solid nu 2 nv 2 nw 2 }" $m "box { min -1 -1 -1 max 1 1 1 surface s }" \
        "f - 1" >"$T/cb.scene"
    t_apply "$T/cb.scene" -o "$T/cb.exr"
    n=$(speckles "$T/cb.exr")
    [ "$n" = 0 ] && ok "a solid checker on a box under the $m mapping: no pixel flipped alone" ||
        notok "checker box under $m speckles" "$n pixels"
done

# ---- the box's faces keep their holes (the issue's box under the solid mapping) ----
cat >"$T/holes.scene" <<'S'
image 64 64
camera { eye 0 0 -5 look 0 0 0 fov 40 }
ambient 1 1 1
texture t holes { solid }
surface s { Ka 1 Kd 0 0 0 apply t { mapping solid Kd = f } }
box { min -1 -1 -1 max 1 1 1 surface s }
S
sed 's/mapping solid/mapping world/' "$T/holes.scene" >"$T/holesw.scene"
for m in holes holesw; do
    t_apply "$T/$m.scene" -o "$T/$m.exr" &&
        t_xform --clip 20,20,44,44 "$T/$m.exr" -o "$T/$m.front.exr" # the front face alone
done
lo=$(info_json "$T/holes.front.exr" stats 0 min)
lw=$(info_json "$T/holesw.front.exr" stats 0 min)
awk -v a="$lo" -v b="$lw" 'BEGIN { exit !(a < 0.5 && b < 0.5) }' &&
    ok "solid holes on a box's front face, on cell faces under the solid and world mappings (min $lo, $lw)" ||
    notok "holes vanish on the box's front face" "min $lo under solid, $lw under world"
