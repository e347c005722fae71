#!/usr/bin/env bash
# --formula thesis: the hole model (5.2.2.6) and the colour variation (5.2.2.7) as the
# thesis prints them, against the scaled forms kept as defaults (t_holes(1), t_colorvar(1)).
. "$(dirname "$0")/../lib.sh"
pfm() { # MAP -> a PFM of its first channel, for python
    t_convert "$1" -o "$T/$(basename "$1" .exr).pfm"
}
# Holes: the same wells (seed, cells, no jitter), R in cells.  The scaled form is
# 1 - e^(-8 R / D), the thesis's 1 - e^(-16 R / D^3): ln(1 - T) in the two stand as 2 / D^2.
for d in 0.5 0.8; do
    t_holes -s 128 --grid-cells 2 --diameter $d --jitter 0 --probability 1 -S 3 -o "$T/s.exr"
    t_holes -s 128 --grid-cells 2 --diameter $d --jitter 0 --probability 1 -S 3 --formula thesis \
        -o "$T/t.exr"
    pfm "$T/s.exr" && pfm "$T/t.exr"
    python3 - "$T/s.pfm" "$T/t.pfm" "$d" <<'P' && ok "holes --formula thesis: ln(1 - T) is 2/D^2 times the scaled form's (D = $d)" || notok "holes thesis D=$d"
import array, math, sys
def load(p):
    d = open(p, "rb").read(); k, s, sc, rest = d.split(b"\n", 3)
    w, h = map(int, s.split()); a = array.array("f"); a.frombytes(rest[:w * h * 4]); return a
s, t, D = load(sys.argv[1]), load(sys.argv[2]), float(sys.argv[3])
want, n, worst = 2 / D ** 2, 0, 0
for a, b in zip(s, t):
    if 1 - a > 1e-3 and 1 - b > 1e-5:
        r = math.log(1 - b) / math.log(1 - a); n += 1; worst = max(worst, abs(r / want - 1))
print("pixels", n, "worst relative error", worst, file=sys.stderr)
sys.exit(0 if n > 20 and worst < 0.02 else 1)
P
done
check_fails "--formula of no such form" 2 t_holes --formula gardner
# Colour variation: one term, no phase shifts: Fact = 0.5 + 0.5 (sin(w u) + 1)(sin(w v) + 1) / 4
t_colorvar -s 64 -f 2 --terms 1 --k1 0 --k2 0 --formula thesis -o "$T/c.exr"
pfm "$T/c.exr"
python3 - "$T/c.pfm" <<'P' && ok "colorvar --formula thesis: 0.5 + 0.5 times the product, no phases" || notok "colorvar thesis"
import array, math, sys
d = open(sys.argv[1], "rb").read(); k, s, sc, rest = d.split(b"\n", 3)
w, h = map(int, s.split()); a = array.array("f"); a.frombytes(rest[:w * h * 4])
worst = 0
for y in range(h):
    for x in range(w):
        u, v = (x + 0.5) / w, (y + 0.5) / h
        want = 0.5 + 0.5 * (math.sin(4 * math.pi * u) + 1) * (math.sin(4 * math.pi * v) + 1) / 4
        worst = max(worst, abs(a[(h - 1 - y) * w + x] - want))
print("worst", worst, file=sys.stderr)
sys.exit(0 if worst < 1e-4 else 1)
P
t_colorvar -s 64 --formula thesis -S 9 -o "$T/c2.exr"
lo=$(info_json "$T/c2.exr" stats 0 min) hi=$(info_json "$T/c2.exr" stats 0 max)
awk -v lo="$lo" -v hi="$hi" 'BEGIN { exit !(lo >= 0.5 && hi <= 1 && hi - lo > 0.1) }' &&
    ok "colorvar --formula thesis lies in [0.5, 1] ($lo..$hi)" || notok "colorvar thesis range" "$lo..$hi"
t_colorvar -s 64 --formula thesis -S 1 -o "$T/p1.exr"
t_colorvar -s 64 --formula thesis -S 2 -o "$T/p2.exr"
same "colorvar --formula thesis has no random phases: the seed changes nothing" "$T/p1.exr" "$T/p2.exr"
