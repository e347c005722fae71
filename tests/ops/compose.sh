#!/usr/bin/env bash
# Composition tools: t_op, t_cascade, t_tile, t_xform, t_warp, t_compose.
. "$(dirname "$0")/../lib.sh"

# Fixtures from the tools themselves: noise, a zero and a one map, a checker, stripes.
t_noise -s 64 -S 3 -f 4 -o "$T/a.exr"
t_noise -s 64 -S 4 -f 4 -o "$T/b.exr"
t_op mul "$T/a.exr" 0 >"$T/zero.exr"
t_op add "$T/zero.exr" 1 >"$T/one.exr"
cat >"$T/cell.tc" <<'S'
tessellation checker_cell; size 16 by 16; cell 8 by 8;
images one = "ONE" 8 by 8; end images;
built with (1,1) one; (2,2) one; end tessellation;
S
sed -i "s|ONE|$T/one.exr|" "$T/cell.tc"
t_compose -o "$T/cell.exr" "$T/cell.tc"
t_tile --nu 8 --nv 8 -s 128 -o "$T/checker.exr" "$T/cell.exr"  # 8-pixel squares
t_tile --nu 64 --nv 64 -s 128 -o "$T/fine.exr" "$T/cell.exr"   # 1-pixel squares
printf 'tessellation stripe; size 16 by 16; cell 8 by 16;\nimages one = "%s" 8 by 16; end images;\nbuilt with (1,1) one; end tessellation;\n' \
    "$T/one.exr" >"$T/stripe.tc"
t_compose "$T/stripe.tc" | t_tile --nu 4 --nv 1 -s 64 -o "$T/stripe.exr" -

# ---- t_op: algebra ----
check "fixtures were made" test -s "$T/checker.exr" -a -s "$T/stripe.exr"
approx "$(info_json "$T/checker.exr" stats 0 mean)" 0.5 1e-6 && ok "checker is half white" ||
    notok "checker is half white"
t_op xor "$T/a.exr" "$T/a.exr" >"$T/x.exr"
approx "$(info_json "$T/x.exr" stats 0 max)" 0 0 && ok "a xor a = 0" || notok "a xor a = 0"
t_op xor "$T/a.exr" "$T/b.exr" >"$T/x.exr"
approx "$(info_json "$T/x.exr" stats 0 max)" 1 0 && ok "a xor b is not all 0" || notok "a xor b"
same "mix weight 0 = a" "$(t_op mix "$T/a.exr" "$T/b.exr" 0 >"$T/m0.exr"; echo "$T/m0.exr")" "$T/a.exr"
same "mix weight 1 = b" "$(t_op mix "$T/a.exr" "$T/b.exr" 1 >"$T/m1.exr"; echo "$T/m1.exr")" "$T/b.exr"
t_op mix "$T/a.exr" "$T/b.exr" "$T/one.exr" >"$T/mw.exr"
same "mix weight map of ones = b" "$T/mw.exr" "$T/b.exr"
# mix is a + (b - a) w in floats, each operand broadcast: an RGB a, a grey b, a grey or RGB
# weight, and a constant, as sub, mul and add give it one step at a time
t_palette marble "$T/a.exr" -o "$T/rgb.exr"
for w in "$T/b.exr" "$T/rgb.exr" 0.3; do
    t_op sub "$T/b.exr" "$T/rgb.exr" | t_op mul - "$w" | t_op add "$T/rgb.exr" - >"$T/steps.exr"
    same "mix of RGB, grey and ${w##*/} is a + (b - a) w, to the bit" \
        <(t_op mix "$T/rgb.exr" "$T/b.exr" "$w") "$T/steps.exr"
done
same "opaque a over b = a" "$(t_op over "$T/a.exr" "$T/b.exr" >"$T/o.exr"; echo "$T/o.exr")" "$T/a.exr"
same "a under opaque b = b" "$(t_op under "$T/a.exr" "$T/b.exr" >"$T/u.exr"; echo "$T/u.exr")" "$T/b.exr"
# A transparent frame around a: over b shows a inside and b outside.
t_xform --expand 96 --background 0,0,0,0 -o "$T/af.exr" "$T/a.exr"
t_xform --expand 96 --background 1,1,1 -o "$T/bw.exr" "$T/one.exr"
t_op over "$T/af.exr" "$T/bw.exr" | t_xform --clip 16,16,80,80 -o "$T/in.exr"
same "a over b inside a's alpha = a" "$T/in.exr" "$T/a.exr"
t_op over "$T/af.exr" "$T/bw.exr" | t_xform --clip 0,0,16,96 -o "$T/out.exr"
approx "$(info_json "$T/out.exr" stats 0 min)" 1 0 && ok "a over b outside a's alpha = b" ||
    notok "a over b outside a's alpha = b"
approx "$(info_json "$T/af.exr" channels)" 4 0 && ok "a transparent background adds alpha" ||
    notok "a transparent background adds alpha"
t_op add "$T/a.exr" "$T/b.exr" | t_op sub - "$T/b.exr" >"$T/ab.exr"
same "(a + b) - b = a" "$T/ab.exr" "$T/a.exr" 1e-6
t_op and "$T/a.exr" "$T/b.exr" >"$T/and.exr"
t_op threshold "$T/a.exr" | t_op mul - "$(t_op threshold "$T/b.exr" >"$T/tb.exr"; echo "$T/tb.exr")" >"$T/and2.exr"
same "a and b = threshold a * threshold b" "$T/and.exr" "$T/and2.exr"
t_op invert "$T/a.exr" | t_op invert - >"$T/ii.exr"
same "invert twice = identity" "$T/ii.exr" "$T/a.exr" 1e-6
t_op add "$T/a.exr" 1,0,0 >"$T/rgb.exr"
approx "$(info_json "$T/rgb.exr" channels)" 3 0 && ok "a grey map broadcasts to RGB" ||
    notok "a grey map broadcasts to RGB"
t_noise -s 32 -o "$T/small.exr"
t_op add "$T/a.exr" "$T/small.exr" --resize scale >/dev/null 2>&1  # options must come first
t_op --resize scale add "$T/a.exr" "$T/small.exr" >"$T/rs.exr"
approx "$(info_json "$T/rs.exr" width)" 64 0 && ok "--resize scale fits operands" ||
    notok "--resize scale fits operands"

# ---- bad input: exit status, one message, nothing written ----
check_fails "unknown operator" 2 t_op -o "$T/no1.exr" frobnicate "$T/a.exr" "$T/b.exr"
check_fails "sizes differ" 2 t_op -o "$T/no2.exr" add "$T/a.exr" "$T/small.exr"
check_fails "channels do not combine" 2 t_op -o "$T/no3.exr" add "$T/rgb.exr" "$T/af.exr" 0,0
check_fails "wrong operand count" 2 t_op -o "$T/no4.exr" mix "$T/a.exr" "$T/b.exr"
check_fails "missing map" 1 t_op -o "$T/no5.exr" add "$T/a.exr" "$T/nothere.exr"
check_fails "two constants" 2 t_op -o "$T/no6.exr" add 1 2
check_fails "cascade without ids" 2 t_cascade -o "$T/no7.exr" "$T/a.exr" 1="$T/b.exr"
check_fails "clip outside the map" 2 t_xform --clip 0,0,65,10 -o "$T/no8.exr" "$T/a.exr"
check_fails "unknown matrix rule" 2 t_tile --matrix spiral -o "$T/no9.exr" "$T/a.exr" "$T/b.exr"
check "nothing was written" test ! -e "$T/no1.exr" -a ! -e "$T/no2.exr" -a ! -e "$T/no3.exr" \
    -a ! -e "$T/no4.exr" -a ! -e "$T/no5.exr" -a ! -e "$T/no6.exr" -a ! -e "$T/no7.exr" \
    -a ! -e "$T/no8.exr" -a ! -e "$T/no9.exr"

# ---- t_xform ----
# A bright block right of centre turns to above centre under +90 degrees.
t_xform --expand 16 --background 0,0,0 "$T/one.exr" | t_xform --expand 64x64 | \
    t_xform --shift 16,0 -o "$T/dot.exr"
t_xform --rotate 90 "$T/dot.exr" | t_xform --clip 24,0,40,32 -o "$T/top.exr"
approx "$(info_json "$T/top.exr" stats 0 max)" 1 0.01 && ok "rotate +90 turns right to up" ||
    notok "rotate +90 turns right to up"
same "shift with wrap, back again = identity" \
    "$(t_xform --shift 10,-7 --wrap "$T/a.exr" | t_xform --shift -10,7 --wrap -o "$T/sh.exr"; echo "$T/sh.exr")" "$T/a.exr"
same "rotate 360 = identity" "$(t_xform --rotate 360 -o "$T/r360.exr" "$T/a.exr"; echo "$T/r360.exr")" "$T/a.exr" 1e-4
# Antialiasing: a 1-pixel checker shrunk 4x is flat grey; nearest sampling would keep 0/1.
t_xform --scale 0.25 -o "$T/shrunk.exr" "$T/fine.exr"
sd=$(info_json "$T/shrunk.exr" stats 0 stddev)
approx "$sd" 0 0.02 && ok "shrunk fine checker does not alias (stddev $sd)" ||
    notok "shrunk fine checker aliases" "stddev $sd"
t_xform --rotate 37 --scale 0.3 -o "$T/rs2.exr" "$T/fine.exr"
t_xform --clip 8,8,30,30 -o "$T/rs3.exr" "$T/rs2.exr"
sd=$(info_json "$T/rs3.exr" stats 0 stddev)
approx "$sd" 0 0.05 && ok "rotated and shrunk fine checker does not alias (stddev $sd)" ||
    notok "rotated shrunk checker aliases" "stddev $sd"
t_xform --rotate 30 -o "$T/rc.exr" "$T/checker.exr"
grey=$(t_xform --clip 32,32,96,96 "$T/rc.exr" | t_op threshold - 0.02 | t_op sub - \
    "$(t_xform --clip 32,32,96,96 "$T/rc.exr" | t_op threshold - 0.98 >"$T/hi.exr"; echo "$T/hi.exr")" |
    t_info --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["stats"][0]["mean"])')
awk -v g="$grey" 'BEGIN { exit !(g > 0.05 && g < 0.6) }' && ok "rotated checker edges are antialiased ($grey grey)" ||
    notok "rotated checker edges" "fraction of grey pixels $grey"
t_xform --expand 300x200 --clip 50,50,250,150 "$T/a.exr" | t_info --json >"$T/ec.json"
grep -q '"width": 200, "height": 100' "$T/ec.json" && ok "expand then clip sizes" ||
    notok "expand then clip sizes"

# ---- t_tile: repetition (Fig. 5.11), mirror (Fig. 5.12), matrix (Fig. 5.8) ----
t_tile --nu 2 --nv 2 -s 128 "$T/a.exr" | t_xform --clip 64,64,128,128 -o "$T/q.exr"
same "a 2x2 repetition repeats the map" "$T/q.exr" "$T/a.exr"
# Mirroring twice flips back: the right half of a mirrored pair, mirrored again.
t_tile --nu 2 --nv 1 --mirror -s 128x64 "$T/a.exr" | t_xform --clip 64,0,128,64 -o "$T/fl.exr"
t_tile --nu 2 --nv 1 --mirror -s 128x64 "$T/fl.exr" | t_xform --clip 64,0,128,64 -o "$T/fl2.exr"
same "mirror twice = identity" "$T/fl2.exr" "$T/a.exr"
d=$(maxdiff "$T/fl.exr" "$T/a.exr")
awk -v d="$d" 'BEGIN { exit !(d > 0.1) }' && ok "mirrored cell differs from the map" ||
    notok "mirrored cell differs from the map" "$d"
t_tile --matrix diagonal --nu 2 --nv 2 -s 128 -o "$T/diag.exr" "$T/a.exr" "$T/b.exr"
printf 'tessellation d; size 128 by 128; cell 64 by 64;\nimages a = "%s"; b = "%s"; end images;\nbuilt with (1,1) a; (2,2) a; (2,1) b; (1,2) b; end tessellation;\n' \
    "$T/a.exr" "$T/b.exr" >"$T/diag.tc"
same "matrix diagonal = a on the diagonal, b elsewhere" "$T/diag.exr" \
    "$(t_compose -o "$T/diag2.exr" "$T/diag.tc"; echo "$T/diag2.exr")"
t_tile --nu 4 --nv 4 -s 64 "$T/stripe.exr" >"$T/srep.exr"
golden "stripe repetition golden (Fig. 5.11)" "$T/srep.exr" compose_stripe_repeat.exr 1e-5
t_xform --rotate 30 "$T/stripe.exr" | t_tile --nu 3 --nv 3 --mirror -s 64 - >"$T/smir.exr"
golden "mirrored stripe golden (Fig. 5.12)" "$T/smir.exr" compose_stripe_mirror.exr 1e-5

# ---- t_cascade (Fig. 5.9 stand-in: ids from a thresholded noise) ----
t_op threshold "$T/a.exr" | t_op add - 1 >"$T/ids.exr"
t_cascade --regions 2 -o "$T/cas.exr" "$T/ids.exr" 1="$T/b.exr"
t_op threshold "$T/a.exr" | t_op invert - | t_op mul - "$T/b.exr" >"$T/cas2.exr"
same "cascade fills region 1, default 0 elsewhere" "$T/cas.exr" "$T/cas2.exr"
t_cascade --regions 2 "$T/ids.exr" 1="$T/a.exr" 2="$T/a.exr" >"$T/cas3.exr"
same "cascade with the same map everywhere = the map" "$T/cas3.exr" "$T/a.exr"
t_cascade --regions 2 --default 1,0,0 "$T/ids.exr" 2="$T/b.exr" | t_info --json >"$T/c.json"
grep -q '"channels": 3' "$T/c.json" && ok "a coloured default makes RGB" || notok "cascade default colour"

# ---- t_warp (Fig. 5.10: turbulence composed with stripes) ----
same "warp by amount 0 = identity" "$(t_warp --displacement 0 "$T/a.exr" "$T/b.exr" >"$T/w0.exr"; echo "$T/w0.exr")" "$T/a.exr"
t_op add "$T/zero.exr" 0.25 >"$T/quarter.exr"
t_warp "$T/a.exr" "$T/quarter.exr" --displacement 1 >"$T/wq.exr"
same "warp by a constant = shift" "$T/wq.exr" "$(t_xform --shift -16,0 --wrap "$T/a.exr" >"$T/sq.exr"; echo "$T/sq.exr")"
t_warp --displacement 0.15 "$T/stripe.exr" "$T/a.exr" >"$T/marble.exr"
golden "turbulence o stripe golden (Fig. 5.10)" "$T/marble.exr" compose_warp_stripe.exr 1e-5
# A thread reuses the displacements of the row below for its next row; threads take rows in
# chunks, so the rows computed afresh differ with -j: the pixels must not.
t_warp -j1 -s 131x67 --displacement 0.4 --isotropic "$T/stripe.exr" "$T/a.exr" >"$T/wj1.exr"
t_warp -j3 -s 131x67 --displacement 0.4 --isotropic "$T/stripe.exr" "$T/a.exr" >"$T/wj3.exr"
same "warp: the same pixels with 1 and 3 threads, odd size" "$T/wj1.exr" "$T/wj3.exr"

# ---- t_compose ----
sed "s|noise(frequency = 6, seed = 3) 200 by 200|noise(frequency = 6, seed = 3) 64 by 64|;
     s|400 by 400|128 by 128|; s|200 by 200;|64 by 64;|; s|300 by 300|96 by 96|;
     s|150, 150|48, 48|; s|50,50 to 250,250|16,16 to 80,80|" \
    "${TEXTURA_TOP:-.}/patterns/tessellation.tc" >"$T/tess.tc"
t_compose -o "$T/tess.exr" "$T/tess.tc"
golden "the thesis's tessellation golden" "$T/tess.exr" compose_tessellation.exr 1e-5
t_compose "$T/tess.tc" | t_xform --clip 64,64,128,128 | t_op sub - \
    "$(t_noise -s 64 -f 6 -S 3 | t_op add - 0,0,0,0 >"$T/n4.exr" 2>/dev/null; t_noise -s 64 -f 6 -S 3 -o "$T/n.exr"; echo "$T/n.exr")" |
    t_info --json >"$T/cell22.json"
python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["stats"]; sys.exit(max(abs(c["max"]) for c in s[:3]) > 1e-6 or max(abs(c["min"]) for c in s[:3]) > 1e-6)' \
    "$T/cell22.json" && ok "cell (2,2) holds image1 unchanged" || notok "cell (2,2) holds image1"
cat >"$T/ops.tc" <<S
tessellation ops; size 64 by 64;
images a = "$T/a.exr"; b = "$T/b.exr"; end images;
c = (a over b) xor (a + 0);
built with (1,1) c; end tessellation;
S
t_compose -o "$T/ops.exr" "$T/ops.tc"
approx "$(info_json "$T/ops.exr" stats 0 max)" 0 0 && ok "script: (a over b) xor a = 0" ||
    notok "script: (a over b) xor a = 0"
printf 'tessellation s; size 64 by 64;\nbuilt with (1,1) "-"; end tessellation;\n' >"$T/stdin.tc"
t_compose "$T/stdin.tc" <"$T/a.exr" >"$T/st.exr"
same "script reads an image from standard input" "$T/st.exr" "$T/a.exr"

bad() { # bad NAME 'script text' 'expected message part'
    printf '%s\n' "$2" >"$T/bad.tc"
    check_fails "script: $1" 2 t_compose -o "$T/bad.exr" "$T/bad.tc"
    if grep -q -- "$3" "$T/.err"; then ok "script: $1 says '$3'"; else notok "script: $1 message" "$(cat "$T/.err")"; fi
}
bad "syntax error" $'tessellation t; size 8 by 8;\nbuilt with (1,1) ; end tessellation;' 'bad.tc:2:18: expected an image'
bad "undefined image" $'tessellation t; size 8 by 8;\nbuilt with (1,1) nothere; end tessellation;' "2:18: undefined image 'nothere'"
bad "recursive definition" $'tessellation t; size 8 by 8;\na = rotate b by 3;\nb = a + 1;\nbuilt with (1,1) a; end tessellation;' 'recursive definition'
bad "absurd size" $'tessellation t; size 65536 by 65536;\nbuilt with end tessellation;' 'larger than the limit'
bad "absurd number" $'tessellation t; size 8 by 99999999;\nbuilt with end tessellation;' '1:27: the size must be a whole number'
bad "defined twice" $'tessellation t; size 8 by 8;\na = noise();\na = noise();\nbuilt with (1,1) a; end tessellation;' 'defined twice'
bad "unknown primitive" $'tessellation t; size 8 by 8;\nbuilt with (1,1) frob(); end tessellation;' "unknown primitive 'frob'"
bad "bad parameter" $'tessellation t; size 8 by 8;\nbuilt with (1,1) noise(frequency = -3); end tessellation;' '2:24: '
bad "cell outside the grid" $'tessellation t; size 8 by 8; cell 4 by 4;\nbuilt with (3,1) noise(); end tessellation;' 'column of a cell'
bad "unterminated string" $'tessellation t; size 8 by 8;\nbuilt with (1,1) "abc; end tessellation;' 'unterminated string'
check "no script output was written" test ! -e "$T/bad.exr"
