# foundation.sh - the stream, files, options and first tools, end to end.
. "$(dirname "$0")/../lib.sh"

# --- pipelines ---
t_noise -s 256 | t_info --json >"$T/info.json"
check "t_noise | t_info --json is valid JSON" python3 -c "import json; json.load(open('$T/info.json'))"
check "t_noise values lie in [0,1] with mean near 0.5" python3 -c "
import json; s = json.load(open('$T/info.json'))['stats'][0]
assert s['min'] >= 0 and s['max'] <= 1 and abs(s['mean'] - 0.5) < 0.05 and s['stddev'] > 0.03, s"
check "t_info reports the size" grep -q '"width": 256, "height": 256, "channels": 1' "$T/info.json"

t_noise -s 64 -S 5 | t_convert | t_info >"$T/hist.txt"
check "each stage appends its command line to the history" \
    grep -qzE 'history:.*t_noise -s 64 -S 5.*t_convert' "$T/hist.txt"

t_noise -s 48x32 | t_convert -o "$T/n.png"
check "t_noise | t_convert -o x.png writes a PNG" bash -c "head -c 8 '$T/n.png' | od -c | grep -q 'P   N   G'"
[ "$(info_json "$T/n.png" width)x$(info_json "$T/n.png" height)" = 48x32 ] && ok "the PNG has the requested size" || notok "the PNG has the requested size"

check "pgmnoise 64 64 | t_info reads netpbm from a pipe" bash -c \
    "pgmnoise 64 64 | t_info --json | grep -q '\"width\": 64, \"height\": 64, \"channels\": 1'"
check "ppm with 16-bit samples from a pipe" bash -c \
    "pgmnoise 16 16 | pgmtoppm '#ff8000' | pamdepth 65535 | t_info --json | grep -q '\"channels\": 3'"

# --- every listed format, read back from a pipe ---
t_noise -s 40x24 -S 9 -o "$T/ref.pfm"
for f in exr png tif ppm pgm pfm bmp tga hdr jpg; do
    t_convert "$T/ref.pfm" -o "$T/x.$f" 2>"$T/err" || { notok "write .$f" "$(cat "$T/err")"; continue; }
    w=$(cat "$T/x.$f" | t_info --json | python3 -c 'import json,sys; v=json.load(sys.stdin); print(v["width"], v["height"], round(v["stats"][0]["mean"], 1))')
    [ "$w" = "40 24 0.5" ] && ok "$f from a pipe reads back ($w)" || notok "$f from a pipe reads back" "got '$w'"
done

# --- bit-exact round trips ---
t_noise -s 33x17 -S 2 -o "$T/a.exr" --compression none
t_convert "$T/a.exr" -o "$T/b.exr" --compression zip
t_convert "$T/b.exr" -o "$T/c.exr" --compression piz
t_convert "$T/a.exr" -o "$T/a.pfm"
t_convert "$T/c.exr" -o "$T/c.pfm"
check "none -> zip -> piz EXR keeps every bit" cmp "$T/a.pfm" "$T/c.pfm"
t_convert "$T/a.exr" | t_convert -o "$T/d.pfm"
check "the stream through a pipe keeps every bit" cmp "$T/a.pfm" "$T/d.pfm"
# chunks that deflate cannot shrink (noise under 3 pixels a cell) are stored raw, not
# as OpenEXR 3.1's predicted bytes (which read back as +-3e38 and NaN)
t_noise -s 256 -f 96 -S 12 --tile -o "$T/fine.pfm"
for c in zip piz; do
    t_convert "$T/fine.pfm" --compression $c -o "$T/fine_$c.exr" && t_convert "$T/fine_$c.exr" -o "$T/fine_$c.pfm"
    check "an incompressible map keeps every bit through $c" cmp "$T/fine.pfm" "$T/fine_$c.pfm"
done
command -v oiiotool >/dev/null && oiiotool --stats "$T/fine_zip.exr" 2>&1 | grep -q "Stats Min: 0.2" &&
    ok "oiiotool reads the incompressible zip file right" || notok "oiiotool reads the zip file"
# a compression is tried batch by batch (eight chunks) while it pays: after a batch that
# shrinks by less than an eighth the next is stored raw and the one after tries only its
# first chunk, one chunk in sixteen.  Noise of cells under a pixel hardly shrinks, and goes
# raw but for the probes; a map of noise above and a constant below (128 chunks) shrinks by
# its lower half but for at most 16 chunks; both read back bit for bit.
t_noise -s 512 -f 300 -S 5 -o "$T/fnz.exr"
t_expr 'if(v < 0.5, noise(frequency = 300), 0.25)' -s 256x2048 -S 5 -o "$T/half.exr"
for m in fnz half; do
    t_convert "$T/$m.exr" | cat >"$T/$m.stream" && t_convert "$T/$m.stream" -o "$T/$m.a.pfm" &&
        t_convert "$T/$m.exr" -o "$T/$m.b.pfm"
    check "a zip file of $m keeps every bit" cmp "$T/$m.a.pfm" "$T/$m.b.pfm"
done
# the chunks stored raw, from the file's offset table: of 32, all but the first batch of
# eight and the probe at chunk 16
raw_chunks() {
    python3 -c '
import struct, sys
d = open(sys.argv[1], "rb").read()
i = 8
while d[i]:  # attributes: name, type, size, value
    i = d.index(b"\0", d.index(b"\0", i) + 1) + 1
    i += 4 + struct.unpack_from("<i", d, i)[0]
offs = struct.unpack_from("<%dQ" % int(sys.argv[2]), d, i + 1)
print(sum(struct.unpack_from("<ii", d, o)[1] == int(sys.argv[3]) for o in offs))' "$@"
}
n=$(raw_chunks "$T/fnz.exr" 32 $((512 * 16 * 4)))
[ "$n" = 23 ] && ok "sub-pixel noise: 23 of its 32 chunks stored raw" ||
    notok "sub-pixel noise stored raw" "$n chunks raw"
f=$(stat -c %s "$T/half.exr") s=$(stat -c %s "$T/half.stream")
[ $((f * 128)) -le $((s * 79)) ] && [ $((f * 100)) -ge $((s * 49)) ] &&
    ok "noise above a constant: the constant compressed ($f of $s bytes)" ||
    notok "noise above a constant compressed" "$f of $s bytes"
# chunks compressed a batch at a time on several threads: the same bytes for any -j, and
# OpenImageIO reads them back bit for bit
for c in zip piz; do
    for j in 1 2 3; do
        t_fractal -s 700x333 -f 5 -S 9 -j $j --compression $c -o "$T/bj.exr" && mv "$T/bj.exr" "$T/bj$j.exr"
    done
    check "$c chunks made on 1, 2 and 3 threads: the same file" \
        bash -c "cmp '$T/bj1.exr' '$T/bj2.exr' && cmp '$T/bj1.exr' '$T/bj3.exr'"
    if command -v oiiotool >/dev/null; then
        t_fractal -s 700x333 -f 5 -S 9 -o "$T/bj.pfm"
        oiiotool "$T/bj2.exr" -d float -o "$T/bj_oiio.tif" 2>/dev/null
        check "oiiotool reads the $c file bit for bit" \
            bash -c "t_convert '$T/bj_oiio.tif' -o '$T/bj_o.pfm' && cmp '$T/bj.pfm' '$T/bj_o.pfm'"
    fi
done
for c in zip piz; do
    t_noise -s 300 -f 700 -S 6 --exr-tiles --compression $c -o "$T/ft_$c.exr" &&
        t_noise -s 300 -f 700 -S 6 -o "$T/ft.pfm" && t_convert "$T/ft_$c.exr" -o "$T/ft_$c.pfm"
    check "a tiled $c file of fine noise keeps every bit" cmp "$T/ft.pfm" "$T/ft_$c.pfm"
done
t_convert "$T/a.exr" -o "$T/e.png" --depth 16
check "16-bit PNG is within one step of 1/65535" python3 -c "
import subprocess, json
a = json.loads(subprocess.check_output(['t_info', '--json', '$T/a.exr']))['stats'][0]
b = json.loads(subprocess.check_output(['t_info', '--json', '$T/e.png']))['stats'][0]
assert abs(a['mean'] - b['mean']) < 2e-5 and abs(a['max'] - b['max']) < 1e-5, (a, b)"
check "--format png writes a PNG to standard output" bash -c "t_noise -s 8 --format png | head -c 4 | grep -q PNG"

# --- interplay with oiiotool ---
oiiotool --pattern checker:width=8:height=8 64x64 3 -d uint8 -o "$T/oiio.tif" 2>/dev/null
check "t_info reads a TIFF written by oiiotool" bash -c \
    "t_info --json '$T/oiio.tif' | grep -q '\"width\": 64, \"height\": 64, \"channels\": 3'"
t_noise -s 32 -o "$T/n.exr"
check "oiiotool reads t_noise's EXR" bash -c "oiiotool --info '$T/n.exr' | grep -q '32 x   32'"
check "oiiotool sees textura:history" bash -c "oiiotool --info -v '$T/n.exr' | grep -q 'textura:history'"

# --- determinism ---
t_noise -s 128 -S 4 -j 1 -o "$T/j1.pfm"
t_noise -s 128 -S 4 -j 2 -o "$T/j2.pfm"
check "the same seed gives the same bytes with 1 and 2 threads" cmp "$T/j1.pfm" "$T/j2.pfm"
t_noise -s 128 -S 5 -o "$T/s5.pfm"
check "another seed gives another map" bash -c "! cmp -s '$T/j1.pfm' '$T/s5.pfm'"

# --- atomic writes ---
echo "old content" >"$T/keep.png"
printf 'v/1\001garbage' >"$T/corrupt.exr"
check_fails "a corrupt EXR is a runtime error" 1 t_convert "$T/corrupt.exr" -o "$T/keep.png"
check "a failed write leaves the old file untouched" grep -q "old content" "$T/keep.png"
check "a failed write leaves no temporary file" bash -c "[ -z \"\$(ls -A '$T' | grep '^\.keep')\" ]"
check_fails "a missing folder is a runtime error" 1 t_noise -s 8 -o "$T/no/such/dir/x.exr"
check "nothing was created" bash -c "[ ! -e '$T/no' ]"
check_fails "an unknown output extension is a usage error" 2 t_noise -s 8 -o "$T/x.xyz"
check "no file for an unknown extension" bash -c "[ ! -e '$T/x.xyz' ]"
check_fails "a float into PNG is a usage error" 2 t_noise -s 8 -o "$T/f.png" --depth 32
check_fails "16 bits into JPEG is a usage error" 2 t_noise -s 8 -o "$T/f.jpg" --depth 16
check_fails "writing onto a folder is a runtime error" 1 t_noise -s 8 -o "$T"

# --- terminals ---
script -qec "t_noise -s 8" /dev/null >"$T/tty.txt" 2>&1
check "image data is never written to a terminal" grep -q "refusing to write image data to a terminal" "$T/tty.txt"
check "the refusal is a one-line message" bash -c "[ \$(grep -c . '$T/tty.txt') = 1 ]"

# --- bad input ---
t_noise -s 64 >"$T/good.exr"
head -c 2000 "$T/good.exr" >"$T/trunc.exr"
check_fails "a truncated stream is a runtime error" 1 t_info "$T/trunc.exr"
check_fails "a truncated pipe is a runtime error" 1 bash -c "head -c 3000 '$T/good.exr' | t_info"
bash -c "head -c 3000 '$T/good.exr' | t_info" 2>"$T/e2"
check "the message names standard input" grep -q "t_info: error: standard input:" "$T/e2"
check_fails "a missing file is a runtime error" 1 t_info "$T/missing.exr"
check_fails "a folder is a runtime error" 1 t_info "$T"
check_fails "empty standard input is a runtime error" 1 bash -c "t_info </dev/null"
check_fails "text is an unknown format" 1 bash -c "echo hello | t_info"
check_fails "a corrupt PNG is a runtime error" 1 bash -c "printf '\211PNG\r\n\032\nxxxxxxxxxxxxxxxx' | t_info"
check_fails "size 0 is a usage error" 2 t_noise -s 0
check_fails "size 10^9 is a usage error" 2 t_noise -s 1000000000
check_fails "a malformed size is a usage error" 2 t_noise -s 10x
check_fails "65537 is over the side limit" 2 t_noise -s 65537
check_fails "65536x65536 held whole is over the sample limit" 2 t_spectral -s 65536
check_fails "NaN frequency is a usage error" 2 t_noise --frequency nan
check_fails "a negative frequency is a usage error" 2 t_noise --frequency -1
check_fails "an unknown option is a usage error" 2 t_noise --octaves 3
check_fails "a missing option value is a usage error" 2 t_noise -s
check_fails "an extra operand is a usage error" 2 t_convert a b c
check_fails "--tile needs a whole frequency" 2 t_noise --tile --frequency 2.5
t_noise --frequency -1 2>"$T/e3"
check "the message names the option and its range" grep -q "frequency must be 0..1000000 (got '-1')" "$T/e3"

# --- tiling ---
t_noise -s 64 --tile -f 4 -o "$T/tile.pfm"
check "--tile makes the map wrap: the seam is as smooth as the interior" python3 -c "
import struct
d = open('$T/tile.pfm', 'rb').read()
head = d.split(b'\n', 3); w = 64
px = struct.unpack('<%df' % (w * w), head[3][:4 * w * w])
row = lambda y: px[y * w:(y + 1) * w]
inner = max(abs(a - b) for y in range(w) for a, b in zip(row(y)[:-1], row(y)[1:]))
seam = max(abs(row(y)[0] - row(y)[-1]) for y in range(w))
vseam = max(abs(a - b) for a, b in zip(row(0), row(w - 1)))
assert seam <= 1.5 * inner and vseam <= 1.5 * inner, (seam, vseam, inner)"

# --- help and man pages ---
check "--help lists every parameter with its default and range" bash -c \
    "t_noise --help | grep -q -- '--frequency F .*\[0..1000000\] (default 8)'"
check "--version names the program" bash -c "t_noise --version | grep -q '^t_noise (Textura)'"
lint=$(mandoc -Tlint -W warning "$TEXTURA_TOP"/man/man*/* 2>&1)
[ -z "$lint" ] && ok "mandoc -Tlint is clean" || notok "mandoc -Tlint is clean" "$(head -3 <<<"$lint")"
"$TEXTURA_TOP/tests/mkman" "$TEXTURA_BUILD/bin" --check
for t in "$TEXTURA_BUILD"/bin/t_*; do
    n=$(basename "$t")
    [ -f "$TEXTURA_TOP/man/man1/$n.1" ] && ok "$n has a man page" || notok "$n has a man page"
done

# --- operands and options in any order ---
t_noise -s 8 -o "$T/o.exr"
check "options may follow the operand" t_convert "$T/o.exr" -o "$T/o2.pfm"
check "a negative number is an operand, not an option" bash -c "t_op add '$T/o.exr' -0.5 | t_info >/dev/null"
check "a negative option value is kept" bash -c "t_noise -s 8 --z -0.5 | t_info | grep -q 'z -0.5'"

# --- OpenMP's idle threads sleep: with libgomp every tool's getenv answers the policy
# (omp_env.c), with LLVM's libomp a tool runs itself again with it set (ld.so starts it
# twice), except when asked for one thread; a policy in the environment is kept
starts() {
    env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u KMP_BLOCKTIME LD_DEBUG=libs "$@" 2>&1 >/dev/null |
        grep -c "initialize program"
}
spin() { # the idle threads' spin count or block time the runtime took, as it displays it
    env -u GOMP_SPINCOUNT -u KMP_BLOCKTIME OMP_DISPLAY_ENV=verbose "$@" 2>&1 >/dev/null |
        grep -E "GOMP_SPINCOUNT = |KMP_BLOCKTIME=" | tail -1 | sed "s/.*= *'//; s/'.*//"
}
want=1 # libgomp, linked statically under gcc (Makefile's PROG_LDLIBS)
ldd "$(command -v t_noise)" | grep -q libomp && want=2
for a in "" "-j 2" "-j 1 -j 2"; do
    n=$(starts t_noise -s 8 $a -q -o "$T/w.pfm")
    w=$(spin env -u OMP_WAIT_POLICY t_noise -s 8 $a -q -o "$T/w.pfm")
    [ "$n" = $want ] && [ "$w" = 0 ] && ok "t_noise ${a:-without -j}: idle threads do not spin (started $n times)" ||
        notok "t_noise ${a:-without -j}: idle threads do not spin" "started $n times (want $want), spin $w"
done
for a in "-j 1" "-j1" "--threads=1" "-j 2 --threads 1"; do
    n=$(starts t_noise -s 8 $a -q -o "$T/w.pfm")
    [ "$n" = 1 ] && ok "t_noise $a (one thread) starts once" ||
        notok "t_noise $a (one thread) starts once" "started $n times"
done
n=$(OMP_WAIT_POLICY=active LD_DEBUG=libs t_noise -s 8 -q -o "$T/w.pfm" 2>&1 | grep -c "initialize program")
w=$(spin env OMP_WAIT_POLICY=active t_noise -s 8 -q -o "$T/w.pfm")
[ "$n" = 1 ] && [ -n "$w" ] && [ "$w" != 0 ] && ok "a policy in the environment is kept (one start, spin $w)" ||
    notok "a policy in the environment is kept" "started $n times, spin '$w'"
