#!/usr/bin/env bash
# t_info --preview: a thumbnail in the terminal, sixel or kitty graphics, decoded here and
# compared with the map it draws.
. "$(dirname "$0")/../lib.sh"
t_checker -s 48x36 --nu 3 --nv 2 -o "$T/c.exr"
t_convert "$T/c.exr" -o "$T/c.pfm"
# decode PROTO: the drawn picture as "w h" then one "r g b" (0..255) per pixel, top row first
decode() {
    python3 -c '
import base64, re, sys
d = sys.stdin.buffer.read().decode("latin-1")
if sys.argv[1] == "kitty":
    chunks = re.findall(r"\x1b_G([^;]*);([^\x1b]*)\x1b\\", d)
    head = dict(kv.split("=") for kv in chunks[0][0].split(","))
    w, h = int(head["s"]), int(head["v"])
    raw = base64.b64decode("".join(c[1] for c in chunks))
    print(w, h)
    for i in range(w * h): print(*raw[3 * i:3 * i + 3])
    sys.exit(0)
body = d[d.index("\x1bPq") + 3:d.index("\x1b\\")]
m = re.match(r"\"1;1;(\d+);(\d+)", body); w, h = int(m.group(1)), int(m.group(2))
body = body[m.end():]
regs, img, x, y, cur, i = {}, {}, 0, 0, 0, 0
while i < len(body):
    c = body[i]
    if c == "#":
        m = re.match(r"#(\d+)(;2;(\d+);(\d+);(\d+))?", body[i:]); i += m.end()
        if m.group(2): regs[int(m.group(1))] = tuple(round(int(v) * 255 / 100) for v in m.group(3, 4, 5))
        else: cur = int(m.group(1))
        continue
    n = 1
    if c == "!":
        m = re.match(r"!(\d+)", body[i:]); n = int(m.group(1)); i += m.end(); c = body[i]
    if c == "$": x = 0
    elif c == "-": x, y = 0, y + 6
    else:
        bits = ord(c) - 63
        for k in range(n):
            for j in range(6):
                if bits >> j & 1: img[x, y + j] = regs[cur]
            x += 1
    i += 1
print(w, h)
for yy in range(h):
    for xx in range(w): print(*img.get((xx, yy), (0, 0, 0)))' "$1"
}
# the map's pixels in 8 bits, as kitty shows them and sixel's registers in percent hold them
expect() {
    python3 - "$T/c.pfm" "$1" <<'P'
import array, sys
d = open(sys.argv[1], "rb").read(); k, s, sc, rest = d.split(b"\n", 3)
w, h = map(int, s.split()); a = array.array("f"); a.frombytes(rest[:w * h * 12])
print(w, h)
for y in range(h):
    for x in range(w):
        v = [min(max(c, 0), 1) for c in a[((h - 1 - y) * w + x) * 3:((h - 1 - y) * w + x) * 3 + 3]]
        b = [int(c * 255 + 0.5) for c in v]
        if sys.argv[2] == "sixel":
            b = [round(((c * 100 + 127) // 255) * 255 / 100) for c in b]
        print(*b)
P
}
for p in sixel kitty; do
    t_info --preview $p "$T/c.exr" | decode $p >"$T/got.$p"
    expect $p >"$T/want.$p"
    cmp -s "$T/got.$p" "$T/want.$p" && ok "--preview $p draws every pixel of the map" ||
        notok "--preview $p" "$(diff "$T/got.$p" "$T/want.$p" | head -3)"
done
t_noise -s 1000x400 | t_info --preview kitty | decode kitty 2>/dev/null | head -1 | grep -qx "256 102" &&
    ok "--preview shrinks a large map to 256 on its longer side" || notok "--preview thumbnail size"
KITTY_WINDOW_ID=1 t_info --preview auto "$T/c.exr" | grep -q $'\e_G' && ok "auto: kitty in kitty" ||
    notok "auto kitty"
TERM=xterm KITTY_WINDOW_ID= t_info --preview auto "$T/c.exr" | grep -q $'\ePq' && ok "auto: sixel elsewhere" ||
    notok "auto sixel"
check_fails "--preview of an unknown protocol" 2 t_info --preview=png "$T/c.exr"
TERM=xterm KITTY_WINDOW_ID= t_info --preview "$T/c.exr" | grep -q $'\ePq' &&
    ok "--preview FILE: the mode picked from the environment" || notok "--preview without a mode"
# A map of many colours (a marble palette over fBm, a grey ramp): sixel's 256 registers and
# error diffusion against kitty's exact picture, compared in 4x4 blocks, as an eye sees them
t_fractal -s 128 -f 4 -S 3 | t_palette marble -o "$T/m.exr"
awk 'BEGIN { print "P2 256 32 255"; for (y = 0; y < 32; y++) { l = "";
    for (x = 0; x < 256; x++) l = l " " x; print l } }' >"$T/ramp.pgm"
for f in m.exr ramp.pgm; do
    t_info --preview sixel "$T/$f" | decode sixel >"$T/s.txt"
    t_info --preview kitty "$T/$f" | decode kitty >"$T/k.txt"
    python3 - "$T/s.txt" "$T/k.txt" "$f" <<'P' && ok "sixel of $f: 4x4 blocks within 3 levels of kitty's, the mean within 1" || notok "sixel of $f"
import sys
def load(p):
    l = open(p).read().split("\n"); w, h = map(int, l[0].split())
    return w, h, [list(map(int, r.split())) for r in l[1:1 + w * h]]
w, h, s = load(sys.argv[1]); _, _, k = load(sys.argv[2])
worst, mean = 0, [0.0] * 3
for by in range(0, h - 3, 4):
    for bx in range(0, w - 3, 4):
        for c in range(3):
            d = sum(s[(by + j) * w + bx + i][c] - k[(by + j) * w + bx + i][c]
                    for j in range(4) for i in range(4)) / 16
            worst = max(worst, abs(d))
for c in range(3):
    mean[c] = abs(sum(p[c] for p in s) - sum(p[c] for p in k)) / len(s)
print(sys.argv[3], "worst block", worst, "mean", mean, file=sys.stderr)
sys.exit(0 if worst <= 3 and max(mean) <= 1 else 1)
P
done
# The thumbnail of a large map is the area mean of its boxes: a 1024x512 map shown 256x128,
# each pixel the mean of its 4x4 box (8-bit, from kitty's exact picture), from the stream and
# from a PNG alike
t_fractal -s 1024x512 -f 8 -S 5 | t_palette marble -o "$T/big.exr"
t_convert "$T/big.exr" -o "$T/big.pfm"
t_convert --depth 16 "$T/big.exr" -o "$T/big.png"
for src in "stream" "png"; do
    case $src in stream) t_info --preview kitty <"$T/big.exr" ;; png) t_info --preview kitty "$T/big.png" ;; esac |
        decode kitty >"$T/th.txt"
    python3 - "$T/big.pfm" "$T/th.txt" <<'P' && ok "--preview of a $src: each thumbnail pixel the mean of its 4x4 box" ||
import array, sys
d = open(sys.argv[1], "rb").read(); k, s, sc, rest = d.split(b"\n", 3)
w, h = map(int, s.split()); a = array.array("f"); a.frombytes(rest[:w * h * 12])
l = open(sys.argv[2]).read().split("\n"); tw, th = map(int, l[0].split())
assert (tw, th) == (256, 128), (tw, th)
worst = 0
for ty in range(th):
    for tx in range(tw):
        got = list(map(int, l[1 + ty * tw + tx].split()))
        for c in range(3):
            m = sum(a[((h - 1 - (4 * ty + j)) * w + 4 * tx + i) * 3 + c] for j in range(4) for i in range(4)) / 16
            worst = max(worst, abs(got[c] - min(max(m, 0), 1) * 255))
sys.exit(0 if worst <= 0.51 else 1)
P
        notok "--preview of a $src: box means" "$(head -c 200 "$T/th.txt")"
done
# a streamed map's thumbnail in bounded memory: a 4096x4096 RGB map (192 MiB as float)
lim=$(stream_vlimit 60000) side=$(stream_side 4096)
t_noise -s $side -f 8 | t_palette --range 0,1 marble |
    (ulimit -v $lim; t_info --preview kitty) | decode kitty >"$T/th.txt"
head -1 "$T/th.txt" | grep -qx "256 256" &&
    ok "--preview of a ${side}x$side stream under ulimit -v $lim KB" || notok "--preview under ulimit -v $lim"
