#!/usr/bin/env bash
# tests/prim/geometry.sh - the geometric primitives from the command line
. "$(dirname "$0")/../lib.sh"

geo="checker circle cycloid ellipse flower four_rings hypocycloid ring stripe
     polygon star grid brick dots"
declare -A nreg=([checker]=2 [circle]=2 [cycloid]=3 [ellipse]=3 [flower]=2 [four_rings]=2
                 [hypocycloid]=3 [ring]=3 [stripe]=2 [polygon]=2 [star]=2 [grid]=2 [brick]=2
                 [dots]=2)

for p in $geo; do
    t_$p -s 128x96 -o "$T/$p.exr"
    t_$p -s 128x96 --ids -o "$T/$p-ids.exr"
    c=$(info_json "$T/$p.exr" channels) s=$(info_json "$T/$p.exr" subregions)
    [ "$c" = 3 ] && [ "$s" = 0 ] && ok "t_$p: RGB by default" || notok "t_$p: RGB by default" "$c channels, $s subregions"
    c=$(info_json "$T/$p-ids.exr" channels) s=$(info_json "$T/$p-ids.exr" subregions)
    lo=$(info_json "$T/$p-ids.exr" stats 0 min) hi=$(info_json "$T/$p-ids.exr" stats 0 max)
    if [ "$c" = 1 ] && [ "$s" = "${nreg[$p]}" ] && approx "$lo" 1 0 && approx "$hi" "$s" 0; then
        ok "t_$p --ids: 1 channel, ids 1..$s"
    else
        notok "t_$p --ids" "$c channels, subregions $s, ids $lo..$hi"
    fi
done

# Area through the CLI: the mean id of a circle map is 1 + pi r^2.
m=$(t_circle --ids -s 256 -r 0.3 | info_json - stats 0 mean)
approx "$m" 1.28274 0.003 && ok "t_circle --ids: mean id 1 + pi r^2" || notok "t_circle area" "$m"
# Colours: black outside, white inside gives the coverage of the disc.
m=$(t_circle -s 256 -r 0.3 --colour1 '#000' --colour2 1,1,1 | info_json - stats 0 mean)
approx "$m" 0.28274 0.002 && ok "t_circle colours: mean is the disc's coverage" || notok "t_circle colours" "$m"
m=$(t_ring --nu 4 --nv 2 -s 256x128 --colour1 '#000' --colour2 '#000' --colour3 '#fff' | info_json - stats 2 mean)
approx "$m" "$(awk 'BEGIN { print 3.14159265 * 0.28 * 0.28 }')" 0.003 &&
    ok "t_ring --nu 4 --nv 2 keeps the inner disc's area" || notok "t_ring repetition" "$m"

# --palette colours region k as t_palette colours id k (antialiasing aside).
a=$(t_ring -s 128 --palette viridis | info_json - stats 1 mean)
b=$(t_ring -s 128 --ids | t_palette viridis | info_json - stats 1 mean)
approx "$a" "$b" 0.01 && ok "t_ring --palette viridis matches t_ring --ids | t_palette viridis" ||
    notok "t_ring --palette" "$a vs $b"
c=$(t_ring -s 128 | info_json - stats 1 mean)
approx "$a" "$c" 0.05 && notok "t_ring --palette changes the colours" "$a vs $c" ||
    ok "t_ring --palette changes the colours"
check_fails "t_ring: unknown palette" 2 t_ring --palette no-such-palette
check_fails "t_ring: --palette with --ids" 2 t_ring --palette viridis --ids

check "t_checker | t_convert -o png" sh -c "t_checker -s 64 | t_convert -o '$T/c.png'"
check "t_stripe --angle 0 --stripe-width 0.2" t_stripe --angle 0 --stripe-width 0.2 -s 32 -o "$T/s.exr"
check "t_ring --tile" t_ring --tile -s 32 -o "$T/r.exr"
check "t_flower --tile with an even rose past the cell" t_flower --tile --rose 4 --petal-length 0.7 -s 32 -o "$T/f.exr"
check_fails "t_flower --tile with petals past the cell" 2 t_flower --tile --petals 4 --petal-length 0.7 -s 32 -o "$T/f.exr"
# --petals N draws N petals, whatever N: count the runs of flower on a circle of radius d/2.
for n in 1 2 3 4 5 6 7 8 12; do
    t_flower -s 256 --petals $n --ids -o "$T/fl.pfm"
    got=$(python3 - "$T/fl.pfm" <<'P'
import struct, sys, math
d = open(sys.argv[1], 'rb').read().split(b'\n', 3)
w, h = map(int, d[1].split()); px = struct.unpack('<%df' % (w * h), d[3][:4 * w * h])
on = [px[int(h / 2 + 0.2 * h * math.sin(t)) * w + int(w / 2 + 0.2 * w * math.cos(t))] == 2
      for t in (2 * math.pi * i / 3600 for i in range(3600))]
print(sum(1 for i in range(3600) if on[i] and not on[i - 1]))
P
)
    [ "$got" = $n ] && ok "t_flower --petals $n draws $n petals" || notok "t_flower --petals $n draws $n petals" "$got"
done
t_flower -s 256 --rose 4 --ids -o "$T/fl.pfm"
t_op sub "$T/fl.pfm" 1 | info_json - stats 0 mean >"$T/rose"
t_flower -s 256 --petals 4 --ids -o "$T/fl.pfm"
t_op sub "$T/fl.pfm" 1 | info_json - stats 0 mean >"$T/petals"
awk -v r="$(cat "$T/rose")" -v p="$(cat "$T/petals")" 'BEGIN { exit !(r > 1.9 * p && r < 2.1 * p) }' &&
    ok "--rose 4 draws the whole rose, twice the petals of --petals 4" || notok "--rose 4" "$(cat "$T/rose") vs $(cat "$T/petals")"

check_fails "t_ring: width above radius" 2 t_ring -r 0.1 --ring-width 0.2
check_fails "t_flower: no petals" 2 t_flower --petals 0
check_fails "t_circle: negative radius" 2 t_circle -r -0.5
check_fails "t_ellipse: minor above major" 2 t_ellipse --semi-major 0.3 --semi-minor 0.4
check_fails "t_ellipse: tilted and too big to tile" 2 t_ellipse --tile --angle 45 --semi-major 0.6 --semi-minor 0.5
check_fails "t_hypocycloid: width above radius" 2 t_hypocycloid -r 0.2 --band-width 0.3
check_fails "t_cycloid: width above the arch" 2 t_cycloid -r 20 --arch-width 0.1
check_fails "t_four_rings: width above radius" 2 t_four_rings -r 0.1 --ring-width 0.2
check_fails "t_stripe: zero width" 2 t_stripe --stripe-width 0
check_fails "t_stripe cannot tile" 2 t_stripe --tile

# A message names a parameter as its row does: the current option, not an old name the row
# still takes (t_ring's -d and --width), and in a scene the row's word.
bad=
while IFS='|' read -r cmd want; do
    got=$($cmd -s 8 2>&1 >/dev/null </dev/null | tail -1)
    [ "$got" = "$want" ] || bad="$bad${bad:+; }$cmd: $got"
done <<'EOF'
t_ring -d 0.9 --radius 0.3|t_ring: error: --ring-width (0.9) must not exceed --radius (0.3)
t_ellipse --semi-major 0.3 --semi-minor 0.4|t_ellipse: error: --semi-minor (0.4) must not exceed --semi-major (0.3)
t_ellipse --semi-minor 0.05|t_ellipse: error: --band-width (0.08) must not exceed --semi-minor (0.05)
t_flower --tile --petal-length 0.7|t_flower: error: --tile with --petals needs --petal-length at most 0.5 (got 0.7)
t_stripe --stripe-width 0|t_stripe: error: --stripe-width must be above 0 (got 0)
t_cycloid -r 20 --arch-width 0.1|t_cycloid: error: --arch-width (0.1) must not exceed the arch's height 0.063662 (--radius 20)
t_hypocycloid -r 0.2 --band-width 0.3|t_hypocycloid: error: --band-width (0.3) must not exceed --radius (0.2)
t_four_rings -r 0.1 --ring-width 0.2|t_four_rings: error: --ring-width (0.2) must not exceed --radius (0.1)
t_perturb --tile --stripes 1.5|t_perturb: error: --stripes must be a whole number with --tile (got 1.5)
t_colorvar --tile --x-phase-frequency 0.5|t_colorvar: error: --x-phase-frequency must be a whole number with --tile (got 0.5)
t_fractal --hurst -20 --lacunarity 16 --octaves 30|t_fractal: error: --hurst: the octave amplitudes overflow (got -20 over 30 octaves)
t_bubble --slice 0.2|t_bubble: error: --slice applies to --dimension 3 only
EOF
[ -z "$bad" ] && ok "messages name the parameters' current options" || notok "messages name options" "$bad"
printf 'image 8 8\ntexture t ring { ring-width 0.9 radius 0.3 }\nsurface s { apply t { Kd = f } }\nsphere { surface s }\n' >"$T/ring.scene"
t_apply "$T/ring.scene" -o "$T/ring.exr" 2>"$T/err"
grep -q ":2:11: ring-width (0.9) must not exceed radius (0.3)$" "$T/err" &&
    ok "a scene's message names the row's word" || notok "a scene's message" "$(cat "$T/err")"
check_fails "t_flower: odd rose past the cell with --tile" 2 t_flower --tile --petals 5 --petal-length 0.7
check_fails "t_checker: bad colour" 2 t_checker --colour1 purpleish
check_fails "t_checker: zero repetitions" 2 t_checker --nu 0

# Man pages: present, options in step with the tools, clean under mandoc.
for p in $geo; do
    page=$TEXTURA_TOP/man/man1/t_$p.1
    if [ ! -f "$page" ]; then
        notok "t_$p.1 exists"
        continue
    fi
    gen=$(t_$p --help-mdoc)
    body=$(awk '/^\.\\" begin options/ { s = 1; next } /^\.\\" end options/ { s = 0 } s' "$page")
    [ "$gen" = "$body" ] && ok "t_$p.1 lists the options of t_$p" || notok "t_$p.1 options differ (make man)"
    if command -v mandoc >/dev/null; then
        lint=$(mandoc -Tlint -W warning "$page" 2>&1)
        [ -z "$lint" ] && ok "t_$p.1 is clean under mandoc" || notok "t_$p.1 mandoc" "$lint"
    else
        skip "t_$p.1 is clean under mandoc" "mandoc is not installed"
    fi
done
