#!/usr/bin/env bash
# The thesis's composition language as it prints it (section 5.2.4.2): its own script, word
# for word, with its Portuguese keywords and a bare map name; its operators written as
# functions; every t_filter operation in scripts; and the tessellations beyond rectangles.
. "$(dirname "$0")/../lib.sh"
top=$(cd "${TEXTURA_TOP:-.}" && pwd)

# says NAME PATTERN: the last failure's one line matches PATTERN
says() { if grep -Eq -- "$2" "$T/.err"; then ok "$1 says '$2'"; else notok "$1 message" "$(cat "$T/.err")"; fi; }
# clip MAP X Y W H OUT: a window of a map
clip() { t_xform --clip "$2,$3,$(($2 + $4)),$(($3 + $5))" -o "$6" "$1"; }

# ---- 1. The thesis's script, exactly as printed: patterns/thesis_tessellation.tc is the
# text of its listing, 'tesselation teste2' to 'end tessellation'.  'leo' is a map named
# bare, as ProSim's files were; here a PNG of noise stands for the photograph. ----
check "the listing is the thesis's text" grep -q '^celula 200 by 200;$' "$top/patterns/thesis_tessellation.tc"
mkdir "$T/th"
t_noise -s 200 -f 6 -S 3 -o "$T/th/leo.png"
t_convert -o "$T/leo.exr" "$T/th/leo.png"
if (cd "$T/th" && t_compose -o out.exr "$top/patterns/thesis_tessellation.tc") 2>"$T/.err"; then
    ok "the thesis's script runs as printed"
else
    notok "the thesis's script runs as printed" "$(cat "$T/.err")"
fi
o=$T/th/out.exr
[ "$(info_json "$o" width)x$(info_json "$o" height)" = 400x400 ] && ok "size 400 by 400" ||
    notok "size 400 by 400" "$(info_json "$o" width)"
# Its regions: (2,2) is leo; (1,1) leo expanded to 300 and centred in its 200 cell, so leo
# again; (2,1) the expanded leo turned 20 degrees about its centre, whose middle 200 x 200
# is (1,2), the clipping from 50,50 to 250,250.  The background 0,0 is transparent.
clip "$o" 200 200 200 200 "$T/c22.exr"
clip "$o" 0 0 200 200 "$T/c11.exr"
clip "$o" 200 0 200 200 "$T/c21.exr"
clip "$o" 0 200 200 200 "$T/c12.exr"
same "cell (2,2) is leo" "$T/c22.exr" "$T/leo.exr"
same "cell (1,1) is leo expanded, centred in its cell" "$T/c11.exr" "$T/leo.exr"
same "cell (1,2), the clipping, is the middle of cell (2,1), the rotation" "$T/c12.exr" "$T/c21.exr"
d=$(maxdiff "$T/c21.exr" "$T/leo.exr")
approx "$d" 0 0.05 && notok "the rotation turns leo" "max diff $d" || ok "the rotation turns leo"
t_xform --rotate 20 --background 0,0,0,0 -o "$T/rot.exr" "$T/leo.exr"
same "the rotation is t_xform's by 20 degrees, with transparent corners" "$T/c21.exr" "$T/rot.exr" 1e-6
approx "$(info_json "$T/c21.exr" stats 3 min)" 0 0 && ok "the rotated cell's corners are transparent" ||
    notok "the rotated cell's corners are transparent"
approx "$(info_json "$T/c11.exr" stats 3 min)" 1 0 && ok "leo's cells are opaque" ||
    notok "leo's cells are opaque"
# A bare name that is neither an image nor a file says so.
printf 'tessellation t; size 8 by 8;\nimages a = nosuchmap 8 by 8; end images;\nbuilt with (1,1) a; end tessellation;\n' >"$T/bare.tc"
check_fails "a bare name with no file" 2 t_compose -o "$T/no.exr" "$T/bare.tc"
says "a bare name with no file" "bare\.tc:2:12: undefined image 'nosuchmap' \(nor a file"

# ---- 2. Portuguese keywords: the same map as the English ones ----
en='tessellation t; size 96 by 64; tessellation brick; cell 32 by 32; background 0.2;
images a = noise(frequency = 3) 24 by 24; end images;
b = expand a to 32 by 32; c = rotate a by 30; d = scale a by 0.5; e = shift a by 3, 4;
f = clipping a from 2,2 to 20,20; g = filter blur a by 1;
built with (1,1) b; (2,1) c; (3,1) d; (1,2) e; (2,2) f; (3,2) g; end tessellation;'
pt=$(sed 's/size/tamanho/; s/brick/tijolo/; s/cell/celula/; s/background/fundo/; s/images/imagens/;
    s/expand/expandir/; s/rotate/rotacionar/; s/scale/escalar/; s/shift/deslocar/;
    s/clipping/recortar/; s/filter/filtro/' <<<"$en")
echo "$en" >"$T/en.tc"
echo "$pt" >"$T/pt.tc"
t_compose -o "$T/en.exr" "$T/en.tc" && t_compose -o "$T/pt.exr" "$T/pt.tc" &&
    same "Portuguese keywords are the English ones" "$T/pt.exr" "$T/en.exr" ||
    notok "Portuguese keywords are the English ones"
grep -q tijolo "$T/pt.tc" && grep -q recortar "$T/pt.tc" && ok "the Portuguese script differs in words" ||
    notok "the Portuguese script differs in words"

# ---- 3. The thesis's operators as functions, against the word forms ----
pair() { # NAME FUNCTIONAL WORDS [TOL]: the two forms give the same map
    for f in a b; do
        printf 'tessellation t; size 64 by 64;\nimages p1 = noise(frequency = 3, seed = 2);\n p2 = expand (filter threshold stripe(spacing = 0.2)) to 48 by 48 background 0,0;\nend images;\nbuilt with (1,1) %s; end tessellation;\n' \
            "$([ $f = a ] && echo "$2" || echo "$3")" >"$T/f$f.tc"
    done
    if t_compose -o "$T/fa.exr" "$T/fa.tc" 2>"$T/.err" && t_compose -o "$T/fb.exr" "$T/fb.tc" 2>>"$T/.err"; then
        same "$1" "$T/fa.exr" "$T/fb.exr" "${4:-0}"
    else
        notok "$1" "$(cat "$T/.err")"
    fi
}
pair "+_up(P1,P2) puts P2 over P1" '+_up(p1, expand p2 to 64 by 64 background 0,0)' \
    '(expand p2 to 64 by 64 background 0,0) over p1'
pair "+_down(P1,P2) puts P2 under P1" '+_down((expand p2 to 64 by 64 background 0,0), p1)' \
    'p1 under (expand p2 to 64 by 64 background 0,0)'
pair "+_up(P1,P2) is not P1 over P2" '+_up(p1, expand p2 to 64 by 64 background 0,0)' \
    'p1 over (expand p2 to 64 by 64 background 0,0)' 2>/dev/null | grep -q '^not ok' &&
    ok "+_up(P1,P2) is not P1 over P2" || notok "+_up(P1,P2) is not P1 over P2"
for op in AND OR XOR; do
    lc=$(tr A-Z a-z <<<"$op")
    pair "$op(P1,P2) is P1 $lc P2" "$op(p1, resize p2 to 64 by 64)" "p1 $lc resize p2 to 64 by 64"
done
pair "and(P1,P2) in lower case" 'and(p1, p1)' 'p1 and p1'
pair "Rotate(alpha, P) turns by alpha radians" 'Rotate(0.5, p1)' 'rotate p1 by 28.64788975654116' 1e-5
pair "Scale(dx, dy, P)" 'resize Scale(2, 0.5, p1) to 64 by 64' 'resize (scale p1 by 2, 0.5) to 64 by 64'
pair "Shift(dx, dy, P)" 'Shift(5, -3, p1)' 'shift p1 by 5, -3'
pair "Filter(name, P)" 'Filter(emboss, p1)' 'filter emboss p1'
pair "rotate (a over b) by d still groups" 'rotate (p1 over p1) by 10' 'rotate p1 by 10'
pair "a signed number after an operand is an operator" 'p1 -1 + 1' 'p1' 1e-6
printf 'tessellation t; size 8 by 8;\nbuilt with (1,1) Rotate(noise(), noise()); end tessellation;\n' >"$T/bad.tc"
check_fails "Rotate takes a number first" 2 t_compose -o "$T/no.exr" "$T/bad.tc"
says "Rotate takes a number first" 'bad\.tc:2:24: expected 1 number and then an image'

# ---- 4. Every t_filter operation in scripts: the same map as t_filter's ----
ops=$(t_filter --help | awk '/one of:/ { f = 1; next } f && /^  [a-z]+ / { print $1 } f && /^$/ { exit }')
[ "$(wc -w <<<"$ops")" -ge 11 ] && ok "t_filter lists its operations ($(wc -w <<<"$ops"))" ||
    notok "t_filter lists its operations" "$ops"
t_noise -s 64 -f 4 -S 5 -o "$T/n.exr"
for op in $ops; do
    printf 'tessellation t; size 64 by 64;\nbuilt with (1,1) filter %s "%s"; end tessellation;\n' "$op" "$T/n.exr" >"$T/op.tc"
    t_filter "$op" -o "$T/want.exr" "$T/n.exr"
    if t_compose -o "$T/got.exr" "$T/op.tc" 2>"$T/.err"; then
        same "script filter $op = t_filter $op" "$T/got.exr" "$T/want.exr"
    else
        notok "script filter $op = t_filter $op" "$(cat "$T/.err")"
    fi
done
# Parameters by name, as t_filter's options.
script_vs_tool() { # NAME SCRIPT-FILTER TOOL-ARGS...
    local name=$1 f=$2
    shift 2
    printf 'tessellation t; size 64 by 64;\nbuilt with (1,1) filter %s; end tessellation;\n' "$f" >"$T/op.tc"
    t_filter "$@" -o "$T/want.exr" "$T/n.exr"
    t_compose -o "$T/got.exr" "$T/op.tc" 2>"$T/.err" && same "$name" "$T/got.exr" "$T/want.exr" ||
        notok "$name" "$(cat "$T/.err")"
}
script_vs_tool "emboss by 2 angle 45 edge wrap" "emboss \"$T/n.exr\" by 2 angle 45 edge wrap" \
    emboss --strength 2 --angle 45 --edge wrap
script_vs_tool "median by 2 edge mirror" "median \"$T/n.exr\" by 2 edge mirror" median -r 2 --edge mirror
script_vs_tool "sobel direction 1" "sobel \"$T/n.exr\" direction 1" sobel --direction
script_vs_tool "noise by 0.1 seed 7" "noise \"$T/n.exr\" by 0.1 seed 7" noise --stddev 0.1 -S 7
script_vs_tool "sharpen by 2 sigma 3" "sharpen \"$T/n.exr\" by 2 sigma 3" sharpen --strength 2 --sigma 3
for bad in 'emboss NOISE radius 3:radius does not apply to filter emboss' \
    'box NOISE by 0:filter box: radius must be 1\.\.1000 \(got 0\)' \
    'smooth NOISE by 2:filter smooth takes no .by.' \
    'nope NOISE:unknown filter .nope. \(one of blur\|threshold\|invert\|abs\|box\|'; do
    f=${bad%%:*}
    printf 'tessellation t; size 64 by 64;\nbuilt with (1,1) filter %s; end tessellation;\n' "${f/NOISE/noise()}" >"$T/bad.tc"
    check_fails "filter ${f/ NOISE/} refused" 2 t_compose -o "$T/no.exr" "$T/bad.tc"
    says "filter ${f/ NOISE/} refused" "${bad#*:}"
done

# ---- 5. Tessellations: every pixel in one cell's shape, each shape its area ----
# Every cell of the grid gets its own grey level (i * 64 + j) / 4096; the counts of each
# level are the cells' areas.
tess() { # KIND W H CW CH COLS ROWS
    {
        printf 'tessellation t; size %s by %s; tessellation %s; cell %s by %s;\n' "$2" "$3" "$1" "$4" "$5"
        printf 'images z = noise() * 0; end images;\nbuilt with\n'
        for ((j = 1; j <= $7; j++)); do
            for ((i = 1; i <= $6; i++)); do printf '(%d,%d) z + %s;\n' $i $j "$(awk -v v=$((i * 64 + j)) 'BEGIN { printf "%.10g", v / 4096 }')"; done
        done
        printf 'end tessellation;\n'
    } >"$T/$1.tc"
    t_compose -o "$T/$1.pfm" "$T/$1.tc"
}
areas() { # KIND CW CH COLS ROWS AREA BLANK: cells away from the edges cover AREA of their box;
    # BLANK: where the background may show
    python3 - "$T/$1.pfm" "$2" "$3" "$4" "$5" "$6" "$7" <<'P'
import struct, sys, collections
path, cw, ch, cols, rows = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
area, blank = float(sys.argv[6]), sys.argv[7]
data = open(path, 'rb').read()
parts = data.split(b'\n', 3)
w, h = map(int, parts[1].split()); scale = float(parts[2])
nc = 3 if parts[0] == b'PF' else 1
px = struct.unpack(('<' if scale < 0 else '>') + 'f' * (w * h * nc), parts[3][:w * h * nc * 4])
count = collections.Counter(); bad = 0
for yy in range(h):
    y = h - 1 - yy  # PFM rows run bottom to top
    for x in range(w):
        v = round(px[(yy * w + x) * nc] * 4096)
        if v == 0 and not eval(blank):
            bad += 1
        count[v] += 1
full = [c for v, c in count.items() if 2 <= v // 64 <= cols - 2 and 2 <= v % 64 <= rows - 2]
want = area * cw * ch
worst = max(abs(c - want) / want for c in full) if full else 1
print(len(full), bad, '%.4f' % worst)
P
}
tess brick 256 192 32 32 9 6
read n bad worst <<<"$(areas brick 32 32 9 6 1 False)"
[ "$n" -gt 5 ] && [ "$bad" = 0 ] && approx "$worst" 0 0 && ok "brick: every pixel in a cell of 32 x 32 ($n inside)" ||
    notok "brick: cells" "$n inside, $bad blank, worst $worst"
tess hexagonal 256 192 32 37 9 7
read n bad worst <<<"$(areas hexagonal 32 37 9 7 0.75 'y < 37 / 4')"
[ "$n" -gt 5 ] && [ "$bad" = 0 ] && approx "$worst" 0 0.03 && ok "hexagonal: each hexagon 3/4 of its box, none blank below the first row's points ($n inside, off by $worst)" ||
    notok "hexagonal: cells" "$n inside, $bad blank, worst $worst"
tess triangular 256 192 32 28 17 7
read n bad worst <<<"$(areas triangular 32 28 17 7 0.5 False)"
[ "$n" -gt 5 ] && [ "$bad" = 0 ] && approx "$worst" 0 0.03 && ok "triangular: each triangle half its box, every pixel in one ($n inside, off by $worst)" ||
    notok "triangular: cells" "$n inside, $bad blank, worst $worst"
# Where the shapes sit: a brick row's first cell is half a cell to the left; triangle (1,1)
# points up, so the bottom-left pixel of the first row is in it.
clip "$T/brick.pfm" 0 32 1 1 "$T/p.exr"
approx "$(info_json "$T/p.exr" stats 0 mean)" "$(awk 'BEGIN { print (64 + 2) / 4096 }')" 1e-6 &&
    ok "brick: (1,2) starts half a cell to the left" || notok "brick: (1,2) starts half a cell to the left"
clip "$T/brick.pfm" 16 32 1 1 "$T/p.exr"
approx "$(info_json "$T/p.exr" stats 0 mean)" "$(awk 'BEGIN { print (128 + 2) / 4096 }')" 1e-6 &&
    ok "brick: (2,2) at half a cell" || notok "brick: (2,2) at half a cell"
clip "$T/triangular.pfm" 0 27 1 1 "$T/p.exr"
approx "$(info_json "$T/p.exr" stats 0 mean)" "$(awk 'BEGIN { print (64 + 1) / 4096 }')" 1e-6 &&
    ok "triangular: (1,1) points up" || notok "triangular: (1,1) points up"
for bad in 'tessellation round:unknown tessellation .round. \(rectangular, hexagonal, triangular or brick\)' \
    'tessellation hexagonal; tessellation brick:the tessellation kind is given twice'; do
    printf 'tessellation t; size 64 by 64; %s; cell 32 by 32;\nbuilt with (1,1) noise(); end tessellation;\n' "${bad%%:*}" >"$T/bad.tc"
    check_fails "${bad%%:*} refused" 2 t_compose -o "$T/no.exr" "$T/bad.tc"
    says "${bad%%:*} refused" "${bad#*:}"
done
