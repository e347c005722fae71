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
[ "$(wc -w <<<"$ids")" = 15 ] && ok "figures.sh makes the 15 figures" || notok "15 figures" "$ids"
for id in $ids; do
    [ -n "${TEXTURA_REGOLD:-}" ] && t_convert -o "$G/figure_$id.exr" "$T/figs/fig_$id.exr"
    same "figure $id matches its golden" "$T/figs/fig_$id.exr" "$G/figure_$id.exr" 1e-5
    grep -q "^!\[$id\](fig_$id.png)" "$T/figs/figures.md" && [ -s "$T/figs/fig_$id.png" ] ||
        notok "figure $id is on the page"
done
n=$(grep -c '^## ' "$T/figs/figures.md")
[ "$n" = 15 ] && ok "the page has a caption for each figure" || notok "captions" "$n"
