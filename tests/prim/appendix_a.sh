#!/usr/bin/env bash
# Appendix A's conventions: center(h, k), the figure's centre in its cell, for every
# geometric primitive; t_stripe's l and d as horizontal components.
. "$(dirname "$0")/../lib.sh"
# centre 0,0 (the lower-left corner, y up) is the default figure moved half a cell left and
# down: with one cell, the map shifted by half its size, wrapped.  Every primitive with the
# row, from the registry.
bad="" n=0
for p in $(t_info --primitives | awk '{ print $1 }'); do
    t_$p --help 2>/dev/null | grep -q -- "--cell-centre" || continue
    n=$((n + 1))
    t_$p -s 64 --ids -o "$T/d.exr" && t_$p -s 64 --ids --cell-centre 0.5,0.5 -o "$T/d2.exr" &&
        [ "$(maxdiff "$T/d.exr" "$T/d2.exr")" = 0 ] || bad="$bad $p(default)"
    t_$p -s 64 --ids --cell-centre 0,0 -o "$T/c.exr" || { bad="$bad $p(run)"; continue; }
    t_xform --shift 32,32 --wrap "$T/d.exr" -o "$T/s.exr"
    [ "$(maxdiff "$T/c.exr" "$T/s.exr")" = 0 ] || bad="$bad $p"
done
[ -z "$bad" ] && [ "$n" -ge 12 ] &&
    ok "--cell-centre 0,0 is the figure moved to its cell's corner, in all $n geometric primitives" ||
    notok "--cell-centre" "$n primitives; wrong:$bad"
t_circle -s 64 --ids --cell-centre 0.25,0.75 -o "$T/q.exr"
t_xform --clip 8,8,24,24 "$T/q.exr" -o "$T/q1.exr"
[ "$(info_json "$T/q1.exr" stats 0 min)" = 2 ] && [ "$(info_json "$T/q.exr" stats 0 min)" = 1 ] &&
    ok "--cell-centre 0.25,0.75 puts the circle in the upper-left quarter" || notok "centre quarter"
# t_stripe --measured horizontal: along a row, each stripe and each gap is l and d long
t_stripe -s 400 --ids -a 60 --stripe-width 0.1 --spacing 0.15 --measured horizontal | t_op sub - 1 |
    t_convert - -o "$T/h.pgm"
python3 - "$T/h.pgm" <<'P' && ok "t_stripe --measured horizontal: runs of 40 and 60 pixels along a row (l 0.1, d 0.15)" || notok "stripe horizontal"
import sys
d = open(sys.argv[1], "rb").read(); parts = d.split(b"\n", 3)
w, h = map(int, parts[1].split()); px = parts[3]
row = px[200 * w:201 * w]
runs, cur, k = [], row[0], 0
for b in row:
    if b == cur: k += 1
    else: runs.append((cur, k)); cur, k = b, 1
inner = runs[1:]  # the first run is cut by the map's edge
hi, lo = max(b for b, _ in inner), min(b for b, _ in inner)
s = [k for b, k in inner if b == hi]; g = [k for b, k in inner if b == lo]
print("stripes", s, "gaps", g, file=sys.stderr)
sys.exit(0 if all(abs(k - 40) <= 1 for k in s) and all(abs(k - 60) <= 1 for k in g) else 1)
P
check_fails "--measured horizontal with horizontal stripes" 2 t_stripe -a 0 --measured horizontal
t_stripe -s 64 -o "$T/a.exr" && t_stripe -s 64 --measured across -o "$T/b.exr" &&
    [ "$(maxdiff "$T/a.exr" "$T/b.exr")" = 0 ] &&
    ok "--measured across is the default, to the byte" || notok "stripe default"
