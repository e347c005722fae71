# files.sh - image files: native PNM/PAM/PFM, PNG, JPEG and TIFF through their
# bridges, EXR variants, files made by netpbm and ImageMagick, and bad files.
. "$(dirname "$0")/../lib.sh"
export TEXTURA_PALETTES="$TEXTURA_TOP/palettes"
IM=$(command -v convert-im6.q16 || command -v convert)

# px MAP: the map's pixels as exact floats, read from the EXR stream t_convert
# writes (scanline, uncompressed, one line per chunk); prints a Python literal
# [w, h, [channel names], [[pixel values]...]] with channels in map order.
cat >"$T/px.py" <<'PY'
import struct, sys
d = sys.stdin.buffer.read()
p, attrs = 8, {}
while d[p] != 0:
    e = d.index(b'\0', p); name = d[p:e].decode(); p = e + 1
    e = d.index(b'\0', p); typ = d[p:e].decode(); p = e + 1
    (n,) = struct.unpack_from('<i', d, p); p += 4
    attrs[name] = (typ, d[p:p + n]); p += n
p += 1
chl, q, chans = attrs['channels'][1], 0, []
while chl[q] != 0:
    e = chl.index(b'\0', q); chans.append(chl[q:e].decode()); q = e + 1 + 16
x0, y0, x1, y1 = struct.unpack('<4i', attrs['dataWindow'][1])
w, h = x1 - x0 + 1, y1 - y0 + 1
p += 8 * h
order = {'R': 0, 'G': 1, 'B': 2, 'A': 3, 'Y': 0}
names = sorted(chans, key=lambda c: order.get(c, 9)) if len(chans) > 1 else chans
if chans == ['A', 'Y']: names = ['Y', 'A']
px = []
for y in range(h):
    p += 8
    row = {c: struct.unpack_from('<%df' % w, d, p + 4 * w * i) for i, c in enumerate(chans)}
    p += 4 * w * len(chans)
    for x in range(w):
        px.append([row[c][x] for c in names])
print(repr([w, h, names, px]))
PY
px() { t_convert "$1" | python3 "$T/px.py"; }
# expect NAME MAP PYTHON-EXPR: ok if the expression holds, with w, h, names, px
# (a list of pixels, each a list of channel values) bound, and F(x) rounding
# an expected value (or a list of them) to float32 as maps hold it.
expect() {
    local got
    if got=$(px "$2" 2>&1 | python3 -c '
import struct, sys
w, h, names, px = eval(sys.stdin.read())
def F(v):  # expected values as the float32 the map holds
    return [F(x) for x in v] if isinstance(v, list) else struct.unpack("f", struct.pack("f", v))[0]
ok = eval(sys.argv[1])
print("" if ok else "w=%d h=%d %s first %s" % (w, h, names, px[:2]))
sys.exit(0 if ok else 1)' "$3" 2>&1); then ok "$1"; else notok "$1" "$(head -c 300 <<<"$got")"; fi
}

# ---- round trips: every native format at 8, 16 and 32 bits, within half a step ----
t_noise -s 61x47 -S 3 -o "$T/g.exr"
t_palette fire "$T/g.exr" -o "$T/c.exr"
t_op mix "$T/c.exr" 0.2,0.9,0.4 "$T/g.exr" -o "$T/c2.exr" # less saturated: no channel clamps
half8=$(awk 'BEGIN { print 0.5 / 255 + 1e-6 }') half16=$(awk 'BEGIN { print 0.5 / 65535 + 1e-7 }')
for case in g:pgm:8 g:pgm:16 c2:ppm:8 c2:ppm:16 g:pnm:16 c2:pnm:8 g:pam:8 c2:pam:16 \
    g:png:8 g:png:16 c2:png:8 c2:png:16 g:tif:8 c2:tif:16 g:tif:32 c2:tif:32 g:pfm:32 c2:pfm:32; do
    IFS=: read -r src ext bits <<<"$case"
    tol=$([ "$bits" = 8 ] && echo "$half8" || { [ "$bits" = 16 ] && echo "$half16" || echo 0; })
    if t_convert "$T/$src.exr" --depth "$bits" -o "$T/rt.$ext" 2>"$T/err"; then
        same "$ext, $bits bits, $(info_json "$T/$src.exr" channels) channels: back within half a step" \
            "$T/$src.exr" "$T/rt.$ext" "$tol"
    else
        notok "write $ext at $bits bits" "$(cat "$T/err")"
    fi
done
# four channels: a PAM RGB_ALPHA and a PNG RGBA keep alpha exactly as stored
python3 -c '
import sys
w, h = 5, 3
px = bytes(v for i in range(w * h) for v in (i * 17 % 256, 255 - i, 3 * i, 128))
sys.stdout.buffer.write(b"P7\nWIDTH %d\nHEIGHT %d\nDEPTH 4\nMAXVAL 255\nTUPLTYPE RGB_ALPHA\nENDHDR\n" % (w, h) + px)' >"$T/a.pam"
expect "PAM RGB_ALPHA reads as stored, not premultiplied" "$T/a.pam" \
    'names == ["R","G","B","A"] and px[4] == F([68/255, 251/255, 12/255, 128/255])'
for ext in png tif pam; do
    t_convert "$T/a.pam" -o "$T/a4.$ext" && t_convert "$T/a4.$ext" -o "$T/a4b.pam" && cmp -s "$T/a.pam" "$T/a4b.pam" &&
        ok "RGBA through $ext comes back byte for byte" || notok "RGBA through $ext" "$(head -c 100 "$T/a4b.pam" | head -6 | tr '\n' ' ')"
done
t_convert "$T/c2.exr" -o "$T/rt.jpg" && d=$(maxdiff "$T/c2.exr" "$T/rt.jpg") && approx "$d" 0 0.05 &&
    ok "JPEG round trip within 0.05 ($d)" || notok "JPEG round trip" "${d:-failed}"
t_convert "$T/g.exr" -o "$T/rt.jpg" && [ "$(info_json "$T/rt.jpg" channels)" = 1 ] &&
    ok "a grey map makes a grey JPEG" || notok "grey JPEG"

# exact values: v / maxval for any maxval, plain and raw, 8 and 16 bits
printf 'P2\n# a comment\n3 1\n1000\n0 333 1000\n' >"$T/p2.pgm"
expect "P2 maxval 1000 reads v/1000" "$T/p2.pgm" 'px == F([[0.0], [333/1000], [1.0]])'
python3 -c 'import sys; sys.stdout.buffer.write(b"P6\n2 1\n65535\n" + bytes([0,1, 0x80,0, 0xff,0xff, 0x12,0x34, 0,0, 0xab,0xcd]))' >"$T/p6.ppm"
expect "P6 16-bit reads big-endian v/65535" "$T/p6.ppm" \
    'px == F([[1/65535, 0x8000/65535, 1.0], [0x1234/65535, 0.0, 0xabcd/65535]])'
printf 'P1\n3 2\n101\n0 1 0\n' >"$T/p1.pbm"
expect "plain PBM: 1 is black (0), 0 is white (1)" "$T/p1.pbm" 'px == [[0.0],[1.0],[0.0],[1.0],[0.0],[1.0]]'
printf 'P4\n10 1\n\x80\x40' >"$T/p4.pbm"
expect "raw PBM packs 8 pixels a byte, padded rows" "$T/p4.pbm" \
    '[v[0] for v in px] == [0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0]'
t_convert "$T/c2.exr" -o "$T/t.pbm" && head -c 3 "$T/t.pbm" | grep -q '^P4' && expect "a .pbm is written as P4" \
    "$T/t.pbm" 'set(v[0] for v in px) <= {0.0, 1.0}' || notok "write .pbm"

# 16-bit PNM for --depth 16, for every PNM extension
for ext in ppm pgm pnm pam; do
    t_convert "$T/c2.exr" --depth 16 -o "$T/d16.$ext" && grep -aq -m1 '^65535$\|^MAXVAL 65535$' "$T/d16.$ext" &&
        ok "--depth 16 writes maxval 65535 to .$ext" || notok "--depth 16 .$ext" "$(head -c 40 "$T/d16.$ext" | tr '\n' ' ')"
done
check_fails "PFM refuses --depth 16" 2 t_convert "$T/g.exr" --depth 16 -o "$T/x.pfm"

# 2-channel maps: RGB with B = 0 where the format has no 2-channel layout
t_d_noise -s 32 -S 5 | t_op mul - 0.25 | t_op add - 0.5 -o "$T/d.exr" # in [0,1]: nothing clamps
for ext in png pam ppm; do
    t_convert "$T/d.exr" --depth 16 -o "$T/d.$ext" && expect "a 2-channel map in .$ext is RGB with B = 0" "$T/d.$ext" \
        'names == ["R","G","B"] and all(p[2] == 0 for p in px)' || notok "write 2 channels to $ext"
done
a=$(px "$T/d.exr") b=$(px "$T/d.png")
python3 -c 'import sys; a, b = eval(sys.argv[1])[3], eval(sys.argv[2])[3]
sys.exit(not all(abs(p[c] - q[c]) <= 0.5 / 65535 + 1e-7 for p, q in zip(a, b) for c in (0, 1)))' "$a" "$b" &&
    ok "its R and G survive the PNG within half a 16-bit step" || notok "R and G through PNG"
t_convert "$T/d.exr" -o "$T/d.tif" && [ "$(info_json "$T/d.tif" channels)" = 2 ] &&
    ok "TIFF keeps 2 channels (an unspecified extra sample, not alpha)" || notok "TIFF 2 channels"

# standard input: native formats by their magic bytes, messages say "standard input"
pgmramp -lr 8 2 | pamtopam >"$T/ramp.pam"
expect "a PAM from pamtopam, from a file" "$T/ramp.pam" 'w == 8 and px[7] == [1.0] and px[0] == [0.0]'
[ "$(pamtopam <"$T/ramp.pam" | t_info | head -1)" = "standard input: 8x2, 1 channel" ] &&
    ok "a PAM on standard input" || notok "PAM on standard input"
printf 'P7\nWIDTH 2\nHEIGHT 2\nDEPTH 7\nMAXVAL 255\nENDHDR\n' >"$T/d7.pam"
check_fails "a PAM of depth 7 on standard input" 1 bash -c "t_info <'$T/d7.pam'"
grep -q '^t_info: error: standard input: PAM depth 7 is not 1..4$' "$T/.err" &&
    ok "the message names standard input and the range" || notok "depth 7 message" "$(cat "$T/.err")"
t_convert "$T/c2.exr" --format png | t_convert --format ppm >"$T/s.ppm" && same "PNG and PPM through pipes" "$T/c2.exr" "$T/s.ppm" "$half8"
# An EXR on a pipe leaves in writes gathered up to 1 MiB (stream.c): a map of 3 MiB, and
# t_apply's bands of 64 rows of over 1 MiB each, keep every pixel
t_noise -s 1100x700 -o "$T/big.exr" && t_convert "$T/big.exr" -o "$T/bigf.pfm" &&
    t_noise -s 1100x700 | t_convert - -o "$T/bigp.pfm" && cmp -s "$T/bigf.pfm" "$T/bigp.pfm" &&
    ok "a 3 MiB map through a pipe" || notok "a 3 MiB map through a pipe"
t_apply "$TEXTURA_TOP/tests/scenes/spheres.scene" -s 1500x130 -j 2 --format pfm >"$T/wf.pfm" &&
    t_apply "$TEXTURA_TOP/tests/scenes/spheres.scene" -s 1500x130 -j 2 -o - |
    t_convert - -o "$T/wp.pfm" && cmp -s "$T/wf.pfm" "$T/wp.pfm" &&
    ok "t_apply's bands of over 1 MiB through a pipe" || notok "t_apply's wide bands through a pipe"

# ---- files made by netpbm and ImageMagick, with and without gAMA ----
ppmmake rgb:ff/80/00 4 2 | pnmtopng >"$T/nb.png"
expect "pnmtopng's PNG" "$T/nb.png" 'px[0] == F([1.0, 128/255, 0.0]) and len(px) == 8'
ppmmake rgb:ff/80/00 4 2 | pnmtopng -gamma 0.45 >"$T/nbg.png"
grep -aq gAMA "$T/nbg.png" && expect "pnmtopng -gamma: the gAMA chunk is ignored, values as stored" "$T/nbg.png" \
    'px[0] == F([1.0, 128/255, 0.0])' || notok "pnmtopng -gamma wrote no gAMA"
pgmmake 0.5 4 2 >"$T/alpha.pgm"
ppmmake rgb:ff/ff/ff 4 2 | pnmtopng -alpha="$T/alpha.pgm" >"$T/na.png"
expect "pnmtopng -alpha: RGBA, colour not premultiplied" "$T/na.png" 'px[0] == F([1.0, 1.0, 1.0, 128/255])'
ppmmake rgb:ff/80/00 3 3 | pnmtopng | pngtopam | pamtopnm >"$T/nr.ppm"
expect "pamtopnm's PPM" "$T/nr.ppm" 'px[4] == F([1.0, 128/255, 0.0])'
pgmramp -lr 256 1 | pamtopam >"$T/r.pam"
expect "pamtopam's GRAYSCALE PAM: every level v reads v/255" "$T/r.pam" \
    'all(px[i] == F([i / 255]) for i in range(256))'
"$IM" -size 4x2 'xc:rgba(255,255,255,0.5)' "$T/im.png" 2>/dev/null
"$IM" -size 4x2 'xc:rgba(255,255,255,0.5)' -define png:exclude-chunks=gAMA,cHRM,sRGB "$T/im0.png" 2>/dev/null
if grep -aq gAMA "$T/im.png" && ! grep -aq gAMA "$T/im0.png"; then
    expect "ImageMagick's RGBA PNG with gAMA: colour 1, alpha 0.5 as stored" "$T/im.png" 'px[0][0] == 1.0 and abs(px[0][-1] - 0.5) < 0.002'
    expect "ImageMagick's RGBA PNG without gAMA: the same values" "$T/im0.png" 'px[0][0] == 1.0 and abs(px[0][-1] - 0.5) < 0.002'
    a=$(px "$T/im.png") b=$(px "$T/im0.png")
    [ "$a" = "$b" ] && ok "the same bytes read the same whatever the gAMA chunk says" || notok "gAMA changes values"
else
    notok "ImageMagick writes a PNG with and without gAMA"
fi
"$IM" -size 3x2 'gradient:#ff8000-#0080ff' -depth 16 "$T/im16.png" 2>/dev/null
expect "ImageMagick's 16-bit PNG" "$T/im16.png" 'w == 3 and max(max(p) for p in px) == 1.0'
"$IM" -size 5x4 xc:'#3366cc' -compress lzw "$T/im.tif" 2>/dev/null
expect "ImageMagick's LZW TIFF" "$T/im.tif" 'px[0][:3] == F([0x33/255, 0x66/255, 0xcc/255])'
"$IM" -size 8x8 xc:'#808080' -quality 100 "$T/im.jpg" 2>/dev/null
expect "ImageMagick's JPEG" "$T/im.jpg" 'all(abs(v - 128/255) < 2/255 for p in px for v in p)'

# ---- EXR: tiled, multi-part, DWAA, more than four channels ----
t_convert "$T/c2.exr" --compression none -o "$T/src.exr"
oiiotool "$T/src.exr" --tile 16 16 -o "$T/tiled.exr" 2>/dev/null
same "a tiled EXR from oiiotool reads as the scanline one" "$T/src.exr" "$T/tiled.exr"
oiiotool "$T/src.exr" --tile 16 16 --compression piz -o "$T/tiledpiz.exr" 2>/dev/null
same "a tiled piz EXR" "$T/src.exr" "$T/tiledpiz.exr"
t_info "$T/tiled.exr" 2>&1 | grep -q "61x47, 3 channels" && ok "t_info reads a tiled EXR" || notok "t_info tiled"
t_info <"$T/tiled.exr" >/dev/null 2>&1 && ok "a tiled EXR on standard input" || notok "tiled EXR on stdin"
oiiotool "$T/src.exr" "$T/g.exr" --siappend -o "$T/multi.exr" 2>/dev/null
same "a two-part EXR reads its first part" "$T/src.exr" "$T/multi.exr"
oiiotool "$T/src.exr" --compression dwaa -o "$T/dwaa.exr" 2>/dev/null
d=$(maxdiff "$T/src.exr" "$T/dwaa.exr" 2>&1) && approx "$d" 0 0.03 && ok "a DWAA EXR is decoded (max diff $d)" ||
    notok "DWAA EXR" "$d"
cat "$T/dwaa.exr" | t_info >/dev/null 2>"$T/err"
grep -q 'standard input: unsupported compression DWAA' "$T/err" && ! grep -qi corrupt "$T/err" &&
    ok "DWAA on a pipe: unsupported compression DWAA, never corrupt" || notok "DWAA on a pipe" "$(cat "$T/err")"
oiiotool "$T/src.exr" --ch R,G,B,A=0.5,Z=2 -o "$T/five.exr" 2>/dev/null
t_convert "$T/five.exr" -o "$T/four.exr" 2>"$T/err"
[ "$(info_json "$T/four.exr" channels)" = 4 ] && ok "a 5-channel EXR keeps four" || notok "5 channels"
[ "$(cat "$T/err")" = "t_convert: warning: $T/five.exr: 5 channels, kept R G B A" ] &&
    ok "with one warning naming the file and the channels kept" || notok "5-channel warning" "$(cat "$T/err")"
t_convert -q "$T/five.exr" -o "$T/four.exr" 2>"$T/err" && [ ! -s "$T/err" ] && ok "-q silences the warning" ||
    notok "-q and the warning" "$(cat "$T/err")"
expect "the kept alpha is the file's A" "$T/four.exr" 'all(p[3] == 0.5 for p in px)'
oiiotool "$T/five.exr" -d float -o "$T/five.tif" 2>/dev/null
t_convert "$T/five.tif" -o "$T/four.exr" 2>"$T/err" && [ "$(info_json "$T/four.exr" channels)" = 4 ] &&
    grep -q "^t_convert: warning: $T/five.tif: 5 channels, the first 4 kept$" "$T/err" &&
    ok "a 5-sample TIFF keeps four, with a warning" || notok "5-sample TIFF" "$(cat "$T/err")"

# ---- bad files: one line naming the file, exit 1, no output ----
bad() { # bad NAME FILE PATTERN: t_convert refuses FILE with a message matching PATTERN
    rm -f "$T/out.png"
    check_fails "$1" 1 t_convert "$2" -o "$T/out.png"
    grep -q "$(basename "$2").*$3" "$T/.err" && [ ! -e "$T/out.png" ] && ok "$1: names the file, no output" ||
        notok "$1: message or output" "$(cat "$T/.err")"
}
printf 'P5\n2 2\n0\n\0\0\0\0' >"$T/m0.pgm"
bad "PNM maxval 0" "$T/m0.pgm" "maxval 0 is not 1..65535"
printf 'P5\n2 2\n70000\n' >"$T/m7.pgm"
bad "PNM maxval 70000" "$T/m7.pgm" "maxval 70000 is not 1..65535"
bad "PAM depth 7" "$T/d7.pam" "PAM depth 7 is not 1..4"
printf 'P5\n2 2\n200\n\0\0\0\xfa' >"$T/big.pgm"
bad "a sample above maxval" "$T/big.pgm" "exceeds maxval"
head -c 30 "$T/d16.ppm" >"$T/tr.ppm"
bad "a truncated PPM" "$T/tr.ppm" "truncated"
t_convert "$T/c2.exr" -o "$T/full.png" && head -c $(($(stat -c %s "$T/full.png") / 2)) "$T/full.png" >"$T/tr.png"
bad "a truncated PNG" "$T/tr.png" "truncated"
t_convert "$T/c2.exr" -o "$T/full.jpg" && head -c $(($(stat -c %s "$T/full.jpg") / 2)) "$T/full.jpg" >"$T/tr.jpg"
bad "a truncated JPEG" "$T/tr.jpg" "Premature end of JPEG"
t_convert "$T/c2.exr" -o "$T/full.tif" && head -c $(($(stat -c %s "$T/full.tif") / 2)) "$T/full.tif" >"$T/tr.tif"
bad "a truncated TIFF" "$T/tr.tif" ": "
python3 - "$T" <<'PY'
import struct, sys, zlib
t = sys.argv[1]
def chunk(k, d): return struct.pack('>I', len(d)) + k + d + struct.pack('>I', zlib.crc32(k + d))
# a bomb: 30000x30000 grey declared (900 MB of pixels), a few hundred bytes given
ihdr = struct.pack('>IIBBBBB', 30000, 30000, 8, 0, 0, 0, 0)
idat = zlib.compress(b'\0' * 30001 * 8)
open(t + '/bomb.png', 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', idat) + chunk(b'IEND', b''))
# a TIFF of width 0 (little-endian, one IFD)
tags = [(256, 3, 1, 0), (257, 3, 1, 4), (258, 3, 1, 8), (259, 3, 1, 1), (262, 3, 1, 1),
        (273, 4, 1, 8 + 2 + 12 * 9 + 4), (277, 3, 1, 1), (278, 3, 1, 4), (279, 4, 1, 0)]
ifd = struct.pack('<H', len(tags)) + b''.join(struct.pack('<HHII', *e) for e in tags) + struct.pack('<I', 0)
open(t + '/w0.tif', 'wb').write(b'II*\0' + struct.pack('<I', 8) + ifd)
PY
# the bomb is refused before allocation: under a 300 MB address-space limit the
# message is the declared size, not "out of memory" (ASan reserves terabytes of
# shadow memory: a sanitizer build runs without the limit)
rm -f "$T/out.png"
lim=300000
nm "$TEXTURA_BUILD/lib/libtex.a" 2>/dev/null | grep -q __asan_ && lim=unlimited
(ulimit -v $lim; t_convert "$T/bomb.png" -o "$T/out.png") 2>"$T/err" </dev/null
st=$?
[ $st = 1 ] && [ "$(wc -l <"$T/err")" = 1 ] && grep -q "bomb.png: PNG declares 30000x30000 pixels, more than its [0-9]* bytes can hold" "$T/err" &&
    [ ! -e "$T/out.png" ] && ok "a PNG bomb is refused before allocation, in one line" || notok "PNG bomb" "exit $st: $(cat "$T/err")"
bad "a TIFF of width 0" "$T/w0.tif" "bad TIFF file (Cannot handle zero"
printf '\x89PNG\r\n\x1a\n' | { t_info 2>"$T/err"; echo $? >"$T/st"; }
[ "$(cat "$T/st")" = 1 ] && grep -q '^t_info: error: standard input: ' "$T/err" &&
    ok "a bare PNG signature on standard input: one line naming standard input" || notok "bare PNG on stdin" "$(cat "$T/err")"
