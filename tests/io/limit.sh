#!/usr/bin/env bash
# limit.sh - the one input limit (io/limit.h, textura(5) "Limits", TEXTURA_MAX_INPUT): every
# reader of a map, a points file or a map inside a scene or script stops at the bytes it has
# read, and a map whose header declares more than the limit is refused before decoding.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# bounded CMD...: run CMD with 2 GB of address space and 20 s at most; on main /dev/zero
# grew without end (8.4 GB in 5 s) and met the ulimit as "out of memory" or a crash.
# A sanitizer build reserves terabytes of shadow and cannot start under ulimit -v: there
# the time bound alone holds.
vlimit=2000000
(ulimit -v $vlimit && t_noise -V) >/dev/null 2>&1 || vlimit=unlimited
bounded() { (ulimit -v $vlimit && timeout 20 "$@") 2>err; }
# refused NAME WHAT CMD...: exit 1 and one line naming WHAT and TEXTURA_MAX_INPUT
refused() {
    local name=$1 what=$2 st
    shift 2
    bounded "$@"
    st=$?
    if [ "$st" = 1 ] && [ "$(wc -l <err)" = 1 ] && grep -q "$what.*TEXTURA_MAX_INPUT" err; then
        ok "$name: refused with one line"
    else
        notok "$name: refused with one line" "exit $st: $(head -c 300 err)"
    fi
}
export TEXTURA_MAX_INPUT=16M
refused "t_info /dev/zero" "/dev/zero: over the input limit of 16777216 bytes" t_info /dev/zero
refused "t_info </dev/zero" "standard input: over the input limit" bash -c 't_info </dev/zero'
refused "a pipe of zeros" "standard input: over the input limit" bash -c 'head -c 40000000 /dev/zero | t_info'
refused "t_convert /dev/zero" "/dev/zero: over" t_convert /dev/zero -o out.exr
refused "t_op, the second map /dev/zero" "/dev/zero: over" t_op add /dev/zero /dev/zero -o out.exr
[ ! -e out.exr ] || notok "a refused input leaves no output" "$(ls)"
cat >zero.scene <<'S'
image 16 16
camera { eye 0 0 -3 look 0 0 0 }
texture t file "/dev/zero"
surface s { Kd 1 apply t { mapping planar Kd = f } }
box { min -1 -1 0 max 1 1 0.1 surface s }
S
refused "a scene's texture file /dev/zero" "zero.scene:3:.*/dev/zero: over" t_apply zero.scene -o out.exr
cat >zero.tc <<'S'
tessellation z;
size 16 by 16;
images
   a = "/dev/zero";
end images;
built with
   (1,1) a;
end tessellation;
S
bounded t_compose zero.tc -o out.exr
st=$?
[ "$st" = 1 ] && grep -q "/dev/zero: over the input limit" err &&
    ok "a script's image /dev/zero: refused" || notok "a script's image /dev/zero: refused" "exit $st: $(cat err)"
# points files: getline grew one line of zeros to 5.3 GB
bounded t_bubble -s 16 --points /dev/zero -o out.exr
st=$?
[ "$st" = 1 ] && grep -q "/dev/zero: larger than 16777216 bytes for a points file" err &&
    ok "t_bubble --points /dev/zero: refused" || notok "t_bubble --points /dev/zero" "exit $st: $(cat err)"
printf '0.5 0.5\n\0\0\0\n' >bin.txt
check_fails "a points file with a NUL: refused" 1 t_bubble -s 16 --points bin.txt -o out.exr

# Declared sizes: refused before decoding, whatever the format, from a file or a pipe.
unset TEXTURA_MAX_INPUT
t_noise -s 64 -o n.exr
t_noise -s 64 -o n.png
t_noise -s 64 -o n.pfm
t_op mul n.exr 0 --compression zip -o z.exr
t_convert n.png -o c.pgm
[ "$(stat -c %s n.pfm)" -gt 15360 ] && TEXTURA_MAX_INPUT=15K check_fails "n.pfm, 16 KiB of bytes: over a 15K limit" 1 t_info n.pfm
grep -q "n.pfm: over the input limit of 15360 bytes" "$T/.err" || notok "n.pfm: the message" "$(cat "$T/.err")"
# compressed files and 8-bit samples (4 bytes as float) are judged by what they declare
for f in z.exr n.png c.pgm; do
    TEXTURA_MAX_INPUT=20K t_info "$f" >/dev/null 2>err && ok "$f: 16 KiB as float passes a 20K limit" ||
        notok "$f: 16 KiB as float passes a 20K limit" "$(cat err)"
    TEXTURA_MAX_INPUT=15K check_fails "$f: 16 KiB as float is over a 15K limit" 1 t_info "$f"
    grep -q "64x64 with 1 channel is 16384 bytes as float, over the input limit of 15360" "$T/.err" ||
        notok "$f: the message gives the size and the limit" "$(cat "$T/.err")"
done
t_noise -s 64 | TEXTURA_MAX_INPUT=15K t_info >/dev/null 2>err
[ $? = 1 ] && grep -q "standard input: 64x64" err && ok "the stream on a pipe: declared size over the limit" ||
    notok "the stream on a pipe: declared size over the limit" "$(cat err)"
# The issue's PNG: 875 KB of deflated zeros declaring 30000x30000, 3.6 GB as float: refused
# at once under the default 2 GiB (on main: 39.7 s, 4.4 GB, exit 0).
python3 - <<'PY'
import struct, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
w = h = 30000
z = zlib.compressobj(9)
row = b'\0' * (w + 1)
data = b''.join(z.compress(row) for _ in range(h)) + z.flush()
open('zeros.png', 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0))
                              + chunk(b'IDAT', data) + chunk(b'IEND', b''))
PY
bounded t_convert zeros.png -o out.exr
st=$?
[ "$st" = 1 ] && grep -q "zeros.png: 30000x30000 with 1 channel is 3600000000 bytes as float, over the input limit of 2147483648 (TEXTURA_MAX_INPUT)" err &&
    [ ! -e out.exr ] && ok "a PNG that inflates to 3.6 GB: refused before decoding" ||
    notok "a PNG that inflates to 3.6 GB: refused before decoding" "exit $st: $(cat err)"
# The variable itself
for v in 12x -5 0 100 1.5G 99999999999999999999G; do
    TEXTURA_MAX_INPUT=$v check_fails "TEXTURA_MAX_INPUT=$v: a usage error" 2 t_info n.exr
    grep -q "TEXTURA_MAX_INPUT must be a size" "$T/.err" || notok "TEXTURA_MAX_INPUT=$v: says so" "$(cat "$T/.err")"
done
TEXTURA_MAX_INPUT= check "TEXTURA_MAX_INPUT empty: the default" t_info n.exr
TEXTURA_MAX_INPUT=1g check "TEXTURA_MAX_INPUT=1g" t_info n.exr
