#!/bin/bash
# Band-limited solid textures in t_apply: `band_limit 1` on turbulence or fBm fades the
# octaves finer than each hit's footprint to their mean.  On a plane running to the
# horizon the far rows lose their aliased roughness and keep their mean, and the fade
# grows with distance (near rows lose less); with `filter off` (no footprints) the
# render is the unfiltered one, byte for byte, and the portable path (TEXTURA_SIMD=scalar)
# renders the same bytes.  Turbulence and fBm (a solid fractal is
# evaluated at the hits, not sampled into a map).
. tests/lib.sh

scene() { # PRIMITIVE BAND FILTER
    cat <<SCENE
image 160 120
samples 1
ambient 1 1 1
filter $3
camera { eye 0 1 -3 look 0 0.7 8 fov 60 }
texture t $1 { solid frequency 6 octaves 8 seed 5 band_limit $2 }
surface s { Ka 1 Kd 1 apply t { mapping solid Kd = f } }
plane { surface s }
SCENE
}
# stats A.pfm Y0 Y1: the mean of channel 0 and the mean |difference| of horizontal
# neighbours over rows [Y0, Y1) (row 0 the top: PFM rows run bottom up)
stats() {
    python3 -c '
import struct, sys
d = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, d[1].split()); c = 3 if d[0] == b"PF" else 1
v = struct.unpack("<%df" % (w * h * c), d[3][:4 * w * h * c])
y0, y1 = int(sys.argv[2]), int(sys.argv[3])
px = lambda x, y: v[((h - 1 - y) * w + x) * c]
rows = range(y0, y1)
mean = sum(px(x, y) for y in rows for x in range(w)) / (len(rows) * w)
rough = sum(abs(px(x + 1, y) - px(x, y)) for y in rows for x in range(w - 1)) / (len(rows) * (w - 1))
print("%.5f %.5f" % (mean, rough))' "$@"
}
for prim in turbulence fractal; do
    scene $prim 0 on >"$T/a.scene"
    scene $prim 1 on >"$T/b.scene"
    scene $prim 0 off >"$T/c.scene"
    scene $prim 1 off >"$T/d.scene"
    t_apply "$T/a.scene" -q -o "$T/a.pfm" && t_apply "$T/b.scene" -q -o "$T/b.pfm" &&
        t_apply "$T/c.scene" -q -o "$T/c.pfm" && t_apply "$T/d.scene" -q -o "$T/d.pfm" ||
        { notok "$prim: band-limited renders" "t_apply failed"; continue; }
    # the horizon is at row 56: far rows 58..72, near rows 100..120
    read -r fa ra <<<"$(stats "$T/a.pfm" 58 72)"
    read -r fb rb <<<"$(stats "$T/b.pfm" 58 72)"
    read -r ma _ <<<"$(stats "$T/a.pfm" 58 120)"
    read -r mb _ <<<"$(stats "$T/b.pfm" 58 120)"
    read -r _ na <<<"$(stats "$T/a.pfm" 100 120)"
    read -r _ nb <<<"$(stats "$T/b.pfm" 100 120)"
    if approx "$fa" "$fb" 0.01 && approx "$ma" "$mb" 0.01 &&
        awk -v a="$ra" -v b="$rb" -v p="$na" -v q="$nb" \
            'BEGIN { exit !(b < 0.5 * a && q / p > 2 * b / a && q < p) }'; then
        ok "$prim band_limit: far rows smoother (roughness $ra -> $rb), near rows less so ($na -> $nb), the same mean ($ma, $mb)"
    else
        notok "$prim band_limit" "mean $ma -> $mb (far $fa -> $fb); roughness far $ra -> $rb, near $na -> $nb"
    fi
    cmp -s "$T/c.pfm" "$T/d.pfm" && ok "$prim band_limit with filter off: the unfiltered render" ||
        notok "$prim band_limit with filter off changed the render"
    # the octaves' weights and the noise at the hits: the portable path's bytes
    TEXTURA_SIMD=scalar t_apply "$T/b.scene" -q -o "$T/e.pfm" && cmp -s "$T/b.pfm" "$T/e.pfm" &&
        ok "$prim band_limit: TEXTURA_SIMD=scalar renders the same bytes" ||
        notok "$prim band_limit under TEXTURA_SIMD=scalar differs"
done
