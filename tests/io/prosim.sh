#!/usr/bin/env bash
# ProSim's headerless files (thesis 5.2, 5.3.1; textura(5)): NAME.r/.g/.b, one byte per
# pixel each, and NAME.pic, floats; the size from the square or NAME_WxH.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1
t_noise -s 64 -S 4 | t_palette marble -o leo.exr
t_convert leo.exr -o leo.r && [ -s leo.r ] && [ -s leo.g ] && [ -s leo.b ] &&
    [ "$(stat -c %s leo.r)" = 4096 ] && ok "-o NAME.r writes NAME.r, .g and .b, a byte a pixel" ||
    notok "writing .r/.g/.b"
t_convert leo.exr -o leo.png
same "the triple reads back as the 8-bit PNG does" leo.g leo.png
# the bytes themselves: each file is its channel of the 8-bit PPM's samples, in order
t_convert leo.png -o leo.ppm
python3 - leo.r leo.g leo.b leo.ppm <<'P' && ok "each file holds its channel's bytes, rows from the top" || notok "byte layout"
import sys
r, g, b = (open(f, "rb").read() for f in sys.argv[1:4])
ppm = open(sys.argv[4], "rb").read().split(b"\n", 3)[3]
assert ppm[0::3] == r and ppm[1::3] == g and ppm[2::3] == b
P
t_info leo.r leo.g leo.b | grep -c "64x64, 3 channels" | grep -qx 3 &&
    ok "any of the three names the triple" || notok "reading by .g or .b"
t_noise -s 48x20 -S 2 -o n_48x20.pic && [ "$(stat -c %s n_48x20.pic)" = $((48 * 20 * 4)) ] &&
    t_noise -s 48x20 -S 2 -o n.exr && same ".pic: floats, exact, the size from the name" n_48x20.pic n.exr
check_fails "a map not square, the size not in the name" 2 t_noise -s 48x20 -o n.pic
[ ! -e n.pic ] && grep -q "n_48x20.pic" "$T/.err" && ok "... says the name to give, writes nothing" ||
    notok "size in the name" "$(cat "$T/.err")"
head -c 1000 /dev/urandom >odd.pic
check_fails "a .pic of a byte count that is no float" 1 t_info odd.pic
head -c 4000 /dev/urandom >r_10x10.pic
check_fails "a size in the name the bytes do not fill" 1 t_info r_10x10.pic
cp leo.r part.r && cp leo.g part.g
check_fails "a triple missing its .b" 1 t_info part.r
grep -q "part.b" "$T/.err" && ok "... names the missing file" || notok "missing .b message" "$(cat "$T/.err")"
check_fails "ProSim's files on standard output" 2 t_noise -s 8 -o r:-
# a composition script's bare map name finds the triple, as the thesis's scripts name leo
cat >s.tc <<'TC'
tessellation t;
size 128 by 128;
tessellation rectangular;
cell 64 by 64;
images
  image1 = leo 64 by 64;
end images;
built with
  (1,1) image1; (2,1) image1; (1,2) image1; (2,2) image1;
end tessellation;
TC
rm -f leo.exr leo.png
t_compose s.tc -o s.exr && [ "$(info_json s.exr channels)" = 3 ] &&
    ok "a script's bare name leo reads leo.r, leo.g, leo.b" || notok "script with leo" "$(t_compose s.tc 2>&1 >/dev/null)"
# a prefix names the format of a name without an extension: the triple takes it as its base
t_noise -s 16 -S 3 -o r:plain && [ -s plain.r ] && [ -s plain.g ] && [ -s plain.b ] &&
    ok "-o r:NAME writes NAME.r, .g and .b" || notok "r: prefix"
check_fails "-o pic:NAME of a map the name does not size" 2 t_noise -s 16x8 -o pic:flat
grep -q "flat_16x8" "$T/.err" && ok "... names flat_16x8" || notok "pic: prefix message" "$(cat "$T/.err")"
