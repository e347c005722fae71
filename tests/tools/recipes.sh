#!/usr/bin/env bash
# The recipes in patterns/: each runs at a small size, from the source tree and from a copy
# laid out as the installed share directory, and writes sane PNG and EXR maps; the tileable
# ones have no seam.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
mkdir -p "$T/share/textura"
cp -R "$top/patterns" "$T/share/textura/patterns"
recipes="wood_plank marble_vase brick_wall granite orange_peel fabric clouds water rust_steel terrain tileable
         composed_marble composed_rings composed_cracks"
for r in $recipes; do
    for where in "$top/patterns" "$T/share/textura/patterns"; do
        label=source; [ "$where" = "$top/patterns" ] || label=installed
        if (cd "$T" && "$where/$r.sh" -o "$T/${label}_$r" -s 48 >"$T/out" 2>"$T/err"); then
            n=$(grep -c "^wrote " "$T/out")
            missing=$(sed -n 's/^wrote \(.*\)\.png and \.exr$/\1/p' "$T/out" | while read -r p; do
                [ -s "$p.png" ] && [ -s "$p.exr" ] || echo "$p"; done)
            [ "$n" -gt 0 ] && [ -z "$missing" ] && ok "recipe $r runs from the $label tree ($n maps)" ||
                notok "recipe $r from the $label tree" "missing: $missing"
        else
            notok "recipe $r runs from the $label tree" "$(head -c 300 "$T/err")"
        fi
    done
done
# every map finite, not flat, but the wood's brightness: uniform over a varnish (thesis 4.5)
bad=0
for f in "$T"/source_*.exr; do
    case $f in */source_wood_plank_brightness.exr)
        approx "$(info_json "$f" stats 0 stddev)" 0 0 || { notok "the wood's brightness is uniform"; bad=1; }
        continue ;;
    esac
    r=$(t_info --json "$f" | python3 -c '
import json, sys
s = json.load(sys.stdin)["stats"]
print("ok" if all(c["nonfinite"] == 0 for c in s) and max(c["stddev"] for c in s[:3]) > 1e-3 else "bad")')
    [ "$r" = ok ] || { notok "$(basename "$f"): finite and not flat"; bad=1; }
done
[ "$bad" = 0 ] && ok "every recipe map is finite and not flat"
check "a recipe's -h prints its header" "$top/patterns/granite.sh" -h
"$top/patterns/granite.sh" -s x12 -o "$T/x" 2>/dev/null; [ $? = 2 ] && ok "a recipe refuses a bad size (exit 2)" ||
    notok "recipe bad size"
# one option set in every recipe, and the tools found beside them (not on PATH)
(cd "$T" && env PATH=/usr/bin:/bin "$top/patterns/granite.sh" -o "$T/bare" -s 40x24 -S 5 >/dev/null) &&
    [ "$(info_json "$T/bare_colour.exr" width)x$(info_json "$T/bare_colour.exr" height)" = 40x24 ] &&
    ok "a recipe finds the tools beside it, and takes -s WxH" || notok "recipe without PATH, -s WxH"
(cd "$T" && "$top/patterns/granite.sh" -o "$T/s0" -s 24 >/dev/null) &&
    (cd "$T" && "$top/patterns/granite.sh" -o "$T/s1" -s 24 -S 1 >/dev/null) &&
    ! cmp -s "$T/s0_colour.exr" "$T/s1_colour.exr" && ok "-S gives another picture" || notok "recipe -S"
for r in synth_tile five_spheres; do
    (cd "$T" && "$top/patterns/$r.sh" -o "$T/$r" -s 32x24 -S 2 >"$T/out" 2>"$T/err") &&
        grep -q "^wrote $T/$r" "$T/out" && ok "$r.sh takes -o, -s WxH and -S as the others do" ||
        notok "$r.sh options" "$(head -c 300 "$T/err")"
done
"$top/patterns/synth_tile.sh" out.png 2>"$T/err"; [ $? = 2 ] && grep -q "unexpected operand" "$T/err" &&
    ok "a recipe refuses an operand" || notok "recipe operand"
# the tileable maps: across the wrap no larger a step than between neighbouring columns
for m in wood stone fabric ground; do
    t_convert "$T/source_tileable_$m.exr" -o "$T/t.pfm"
    r=$(python3 - "$T/t.pfm" <<'P'
import array, sys
d = open(sys.argv[1], 'rb').read(); k, s, sc, rest = d.split(b'\n', 3)
w, h = map(int, s.split()); nc = 3 if k == b'PF' else 1
a = array.array('f'); a.frombytes(rest[:w * h * nc * 4])
px = lambda x, y: a[(y * w + x) * nc:(y * w + x) * nc + nc]
def step(x0, x1): return sum(abs(p - q) for y in range(h) for p, q in zip(px(x0, y), px(x1, y))) / h
inner = sum(step(x, x + 1) for x in range(w - 1)) / (w - 1)
rows = lambda y0, y1: sum(abs(p - q) for x in range(w) for p, q in zip(px(x, y0), px(x, y1))) / w
inner_v = sum(rows(y, y + 1) for y in range(h - 1)) / (h - 1)
print("ok" if step(w - 1, 0) < 3 * inner + 1e-6 and rows(h - 1, 0) < 3 * inner_v + 1e-6 else
      "seam %.4f %.4f vs %.4f %.4f" % (step(w - 1, 0), rows(h - 1, 0), inner, inner_v))
P
)
    [ "$r" = ok ] && ok "tileable $m has no seam" || notok "tileable $m" "$r"
done
