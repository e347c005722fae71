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
# the map's pixels as the 6x6x6 cube (sixel) or 8 bits (kitty) would show them
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
            b = [round(((c * 5 + 127) // 255) * 20 * 255 / 100) for c in b]
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
check_fails "--preview of an unknown protocol" 2 t_info --preview png "$T/c.exr"
