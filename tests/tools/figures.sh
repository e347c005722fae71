#!/usr/bin/env bash
# `make figures`: every figure patterns/figures.sh rebuilds matches its golden image (at
# 64 pixels; within 1e-5: the renders and maps are deterministic on any compiler and -j),
# and its page shows each one with its caption.
. "$(dirname "$0")/../lib.sh"
G=${TEXTURA_TOP:-.}/tests/golden
top=${TEXTURA_TOP:-.}
if ! "$top/patterns/figures.sh" -o "$T/figs" -s 64 >"$T/out" 2>&1; then
    notok "figures.sh runs" "$(tail -3 "$T/out")"
    exit 0
fi
ids=$(sed -n 's/^wrote fig_\(.*\)$/\1/p' "$T/out")
[ "$(wc -w <<<"$ids")" = 19 ] && ok "figures.sh makes the 19 figures" || notok "19 figures" "$ids"
for id in $ids; do
    [ -n "${TEXTURA_REGOLD:-}" ] && t_convert -o "$G/figure_$id.exr" "$T/figs/fig_$id.exr"
    same "figure $id matches its golden" "$T/figs/fig_$id.exr" "$G/figure_$id.exr" 1e-5
    grep -q "^!\[$id\](fig_$id.png)" "$T/figs/figures.md" && [ -s "$T/figs/fig_$id.png" ] ||
        notok "figure $id is on the page"
done
n=$(grep -c '^## ' "$T/figs/figures.md")
[ "$n" = 19 ] && ok "the page has a caption for each figure" || notok "captions" "$n"
# The page names the recipes by their place in the tree, not the machine that built it.
grep -q "'/" "$T/figs/figures.md" && notok "the page has no absolute paths" "$(grep -m1 "'/" "$T/figs/figures.md")" ||
    ok "the page has no absolute paths"
# Figure 5.10 has no seam: its last two columns differ no more than two columns inside do.
coldiff() { # MAP X: mean |column X - column X+1|
    t_xform --clip "$2,0,$(($2 + 1)),64" -o "$T/c0.exr" "$1"
    t_xform --clip "$(($2 + 1)),0,$(($2 + 2)),64" -o "$T/c1.exr" "$1"
    t_op sub "$T/c0.exr" "$T/c1.exr" | t_op abs - | t_info --json | awk -F'"mean": ' '/"channel"/ { v = $2; sub(/,.*/, "", v); print v; exit }'
}
edge=$(coldiff "$T/figs/fig_5.10.exr" 62)
inside=$(awk -v a="$(coldiff "$T/figs/fig_5.10.exr" 20)" -v b="$(coldiff "$T/figs/fig_5.10.exr" 40)" 'BEGIN { print (a + b) / 2 }')
awk -v e="$edge" -v i="$inside" 'BEGIN { exit !(e <= 2 * i + 0.01) }' && ok "figure 5.10 has no seam at its right edge ($edge against $inside inside)" ||
    notok "figure 5.10 has no seam at its right edge" "$edge against $inside inside"
