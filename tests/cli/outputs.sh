#!/usr/bin/env bash
# Output names as ImageMagick's and netpbm's users write them (textura(5), Output names):
# a FMT: prefix, --format with -o, streams without an extension, .ppm/.pgm/.pnm; and
# t_info taking several maps, as identify does.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1
t_noise -s 24x16 -S 3 -o n.exr
t_palette marble n.exr -o rgb.exr
magic() { head -c "$1" | od -An -c | tr -d ' \n'; }

# 1. Standard output by name, and streams without an extension: the EXR stream
[ "$(t_noise -s 24x16 -S 3 -o /dev/stdout | magic 4)" = "v/1001" ] &&
    ok "-o /dev/stdout writes the EXR stream" || notok "-o /dev/stdout"
[ "$(t_noise -s 24x16 -S 3 -o /dev/fd/1 | magic 4)" = "v/1001" ] &&
    ok "-o /dev/fd/1 writes the EXR stream" || notok "-o /dev/fd/1"
t_noise -s 24x16 -S 3 -o /dev/fd/3 3>fd3.out && t_info fd3.out | grep -q "24x16" &&
    ok "-o /dev/fd/3 writes the descriptor the shell opened" || notok "-o /dev/fd/3"
mkfifo fifo
(cat fifo >fifo.out) &
t_noise -s 24x16 -S 3 -o fifo
wait
same "-o FIFO without an extension: the stream, the same map" fifo.out n.exr
t_noise -s 24x16 -S 3 -o /dev/stdout | t_op sub - n.exr | t_info --json |
    grep -q '"max": 0,' && ok "/dev/stdout carries the same pixels" || notok "/dev/stdout pixels"

# 2. --format with -o -, with an extensionless name, and against an extension
[ "$(t_noise -s 24x16 --format png -o - | magic 4)" = "211PNG" ] &&
    ok "--format png -o - writes PNG" || notok "--format png -o -"
t_noise -s 24x16 --format tif -o out.dat && [ "$(magic 2 <out.dat)" = "II" ] &&
    ok "--format tif -o out.dat writes TIFF" || notok "--format tif -o out.dat"
check_fails "--format against -o's extension" 2 t_noise -s 8 --format tif -o x.png
grep -q "contradicts the extension of x.png" "$T/.err" && [ ! -e x.png ] &&
    ok "... says so and writes nothing" || notok "--format contradiction message" "$(cat "$T/.err")"
check_fails "--format of no known format" 2 t_noise -s 8 --format xyz -o -

# 3. ImageMagick's FMT: prefixes
[ "$(t_noise -s 24x16 -o png:- | magic 4)" = "211PNG" ] && ok "-o png:- writes PNG" ||
    notok "-o png:-"
t_noise -s 24x16 -S 3 -o exr:out.bin && same "-o exr:out.bin writes an EXR file" out.bin n.exr
t_noise -s 24x16 -o jpg:x.exr && [ "$(magic 3 <x.exr)" = "377330377" ] &&
    ok "a prefix wins over the extension, as in ImageMagick" || notok "jpg:x.exr"
t_palette marble n.exr -o png:- | t_info - | grep -q "3 channels" &&
    ok "a prefix on a map tool's output" || notok "t_palette -o png:-"
check_fails "a prefix against --format" 2 t_noise -s 8 --format tif -o png:y
check_fails "a name with no extension, a regular file" 2 t_noise -s 8 -o plain
[ ! -e plain ] && grep -q "png:plain" "$T/.err" && ok "... names the prefix that would do" ||
    notok "no extension message" "$(cat "$T/.err")"
mkdir folder
check_fails "a folder without an extension" 1 t_noise -s 8 -o folder
t_noise -s 32 | t_apply -s 16x12 -q -o png:- "${TEXTURA_TOP:-.}/tests/scenes/stdin.scene" |
    magic 4 | grep -qx "211PNG" && ok "t_apply -o png:-" || notok "t_apply -o png:-"

# 4. Extensions mean formats: .ppm is P6, .pgm P5, .pnm lets the map choose
t_convert n.exr -o g.ppm && [ "$(magic 2 <g.ppm)" = "P6" ] &&
    ok ".ppm of a grey map is P6" || notok ".ppm grey"
m=$(info_json n.exr stats 0 mean)
t_info --json g.ppm | python3 -c 'import json,sys
s = json.load(sys.stdin)["stats"]; assert len(s) == 3
assert all(abs(c["mean"] - float(sys.argv[1])) < 0.003 for c in s), s' "$m" &&
    ok "... with the grey in R, G and B" || notok ".ppm grey channels"
t_convert rgb.exr -o c.pgm && [ "$(magic 2 <c.pgm)" = "P5" ] &&
    ok ".pgm of a colour map is P5" || notok ".pgm colour"
# ppmtopgm's weights
want=$(t_info --json rgb.exr | python3 -c 'import json,sys
s = json.load(sys.stdin)["stats"]; print(0.299 * s[0]["mean"] + 0.587 * s[1]["mean"] + 0.114 * s[2]["mean"])')
got=$(info_json c.pgm stats 0 mean)
approx "$got" "$want" 0.003 && ok ".pgm is ppmtopgm's grey (mean $got, want $want)" ||
    notok ".pgm weights" "$got vs $want"
if command -v ppmtopgm >/dev/null; then
    t_convert rgb.exr -o c.ppm && ppmtopgm c.ppm >ref.pgm 2>/dev/null &&
        same ".pgm agrees with netpbm's ppmtopgm" c.pgm ref.pgm 0.0040
fi
t_convert n.exr -o g.pnm && [ "$(magic 2 <g.pnm)" = "P5" ] && t_convert rgb.exr -o c.pnm &&
    [ "$(magic 2 <c.pnm)" = "P6" ] && ok ".pnm: P5 for grey, P6 for colour" || notok ".pnm"
t_noise -s 24x16 -o - | t_convert -o g2.ppm - && [ "$(magic 2 <g2.ppm)" = "P6" ] &&
    ok ".ppm written a band at a time is P6 too" || notok ".ppm streamed"

# 5. t_info takes several maps, one report each, as identify does
t_info n.exr rgb.exr >two.txt && [ "$(grep -c "^n.exr: 24x16\|^rgb.exr: 24x16" two.txt)" = 2 ] &&
    ok "t_info A B reports both" || notok "t_info A B" "$(cat two.txt)"
t_info n.exr missing.exr rgb.exr >some.txt 2>some.err
st=$?
[ $st = 1 ] && [ "$(wc -l <some.err)" = 1 ] && grep -q "^t_info: error: missing.exr" some.err &&
    grep -q "^rgb.exr: 24x16" some.txt && ok "a missing map: one line, status 1, the rest reported" ||
    notok "t_info with a missing map" "status $st: $(cat some.err)"
t_info --json n.exr rgb.exr | python3 -c 'import json,sys
v = json.load(sys.stdin); assert [d["file"] for d in v] == ["n.exr", "rgb.exr"], v
assert v[1]["channels"] == 3' && ok "--json of several maps is an array, each naming its file" ||
    notok "t_info --json A B"
t_noise -s 8 | t_info --json | python3 -c 'import json,sys; assert json.load(sys.stdin)["width"] == 8' &&
    ok "--json of one map is one object" || notok "t_info --json one"
