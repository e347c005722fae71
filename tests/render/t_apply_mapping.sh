#!/usr/bin/env bash
# t_apply's mappings (thesis 5.3.1): the face id in application functions, fixed-size
# (non-elastic) mapping, P as a target and the infinite cone.
. "$(dirname "$0")/../lib.sh"

# counts MAP: "value count" of the red channel's values (rounded to 1e-4), one per line
counts() {
    local pfm
    pfm=$(mktemp "$T/px.XXXXXX").pfm
    t_convert -o "$pfm" "$1" && python3 - "$pfm" <<'P'
import array, collections, sys
d = open(sys.argv[1], 'rb').read()
kind, size, scale, rest = d.split(b'\n', 3)
w, h = map(int, size.split())
nc = 3 if kind == b'PF' else 1
a = array.array('f'); a.frombytes(rest[:w * h * nc * 4])
if float(scale) > 0: a.byteswap()
for v, n in sorted(collections.Counter(round(a[i * nc], 4) for i in range(w * h)).items()):
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
