# reliability.sh - nothing left behind on a signal, text output errors,
# terminals on stdin and stdout, special output paths (FIFO, device, symlink).
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# pty_run CMD...: run CMD with a terminal on stdin, stdout and stderr (python's pty);
# prints what it wrote, then "exit N".  Gives up after 20 s ("exit hung").
pty_run() {
    python3 - "$@" <<'PY'
import os, pty, select, signal, sys, time
pid, fd = pty.fork()
if pid == 0:
    os.execvp(sys.argv[1], sys.argv[1:])
out, st, end = b"", None, time.time() + 20
while time.time() < end and st is None:
    r, _, _ = select.select([fd], [], [], 0.1)
    if r:
        try:
            out += os.read(fd, 4096)
        except OSError:
            pass
    p, s = os.waitpid(pid, os.WNOHANG)
    if p:
        st = s
if st is None:
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
print(out.decode(errors="replace"))
print("exit hung" if st is None else "exit %s" % (os.WEXITSTATUS(st) if os.WIFEXITED(st) else "signal"))
PY
}

# kill_during_write SIG OUT CMD...: start CMD, send SIG once the temporary file
# .OUT.* exists; prints "seen|unseen STATUS LEFTOVER".
kill_during_write() {
    local sig=$1 out=$2 pid seen=unseen st
    shift 2
    "$@" 2>/dev/null &
    pid=$!
    for _ in $(seq 1200); do
        compgen -G ".$out.*" >/dev/null && seen=seen && break
        sleep 0.025
    done
    kill -"$sig" "$pid"
    [ -n "${TWICE:-}" ] && kill -"$sig" "$pid" 2>/dev/null
    wait "$pid"
    st=$?
    echo "$seen $st $(compgen -G ".$out.*")"
}

# --- 3: a signal during the write removes the temporary file, then ends the process ---
for sig in INT TERM HUP PIPE; do
    rm -f big.png .big.png.*
    # env --default-signal: a background job of a script starts with SIGINT ignored.
    read -r seen st left <<<"$(kill_during_write "$sig" big.png env --default-signal t_noise -s 6000 -o big.png)"
    want=$((128 + $(kill -l "$sig")))
    if [ "$seen" != seen ]; then
        notok "SIG$sig during the write" "no temporary file was seen"
    elif [ -n "$left" ]; then
        notok "SIG$sig during the write leaves nothing" "left $left"
    elif [ "$st" != "$want" ]; then
        notok "SIG$sig during the write ends by the signal" "exit $st, wanted $want"
    else
        ok "SIG$sig during the write leaves no temporary file, ends by the signal"
    fi
done
# t_apply writes an EXR as it renders it, a band of rows at a time: killed mid-render, it
# leaves neither the file nor its temporary one.
rm -f big.exr .big.exr.*
read -r seen st left <<<"$(kill_during_write TERM big.exr t_apply "$TEXTURA_TOP/tests/scenes/spheres.scene" \
    -s 4000x4000 -j 1 -o big.exr)"
[ "$seen" = seen ] && [ -z "$left" ] && [ ! -e big.exr ] && [ "$st" = 143 ] &&
    ok "SIGTERM during t_apply's render in bands leaves nothing" ||
    notok "SIGTERM during t_apply's render in bands leaves nothing" "$seen exit $st left $left"
rm -f big.exr .big.exr.*
# timeout(1) signals the child, then its process group: two signals at once.
rm -f big.png .big.png.*
read -r seen st left <<<"$(TWICE=1 kill_during_write TERM big.png t_noise -s 6000 -o big.png)"
[ "$seen" = seen ] && [ -z "$left" ] && [ "$st" = 143 ] && ok "two SIGTERMs at once leave nothing" ||
    notok "two SIGTERMs at once leave nothing" "$seen exit $st left $left"
rm -f big.png .big.png.*
# The issue's case: killed by timeout(1) at any moment, nothing hidden remains.
timeout -s TERM 2 t_noise -s 12000 -o big.png 2>/dev/null
if compgen -G '.big.png.*' >/dev/null; then
    notok "timeout -s TERM t_noise -s 12000 leaves nothing" "$(ls -a)"
else
    ok "timeout -s TERM t_noise -s 12000 leaves nothing"
fi
rm -f big.png
# A signal the parent ignores (nohup) stays ignored.
read -r seen st left <<<"$(trap '' HUP; kill_during_write HUP hup.png t_noise -s 6000 -o hup.png)"
if [ "$seen" = seen ] && [ "$st" = 0 ] && [ -f hup.png ] && [ -z "$left" ]; then
    ok "an ignored SIGHUP stays ignored"
else
    notok "an ignored SIGHUP stays ignored" "$seen exit $st $left"
fi

# --- 5: text output that does not reach standard output is an error ---
for a in -h -V; do
    t_noise "$a" >/dev/full 2>err
    st=$?
    if [ "$st" = 1 ] && grep -q '^t_noise: error: standard output: No space' err; then
        ok "t_noise $a >/dev/full exits 1"
    else
        notok "t_noise $a >/dev/full exits 1" "exit $st: $(cat err)"
    fi
done
t_apply "$TEXTURA_TOP/tests/scenes/spheres.scene" -s 64x200 -o - >/dev/full 2>err
st=$?
[ "$st" = 1 ] && grep -q '^t_apply: error: standard output: write error: No space' err &&
    ok "t_apply's EXR in bands >/dev/full exits 1" ||
    notok "t_apply's EXR in bands >/dev/full exits 1" "exit $st: $(cat err)"
# a reader that leaves early, SIGPIPE ignored: the writes gathered up to 1 MiB (stream.c)
# fail later than the first, when a band is done or the gathered MiB is full: still an error;
# rows of 32 KiB and more (9000 wide) leave by writev, not through the stage
for cmd in "t_apply $TEXTURA_TOP/tests/scenes/spheres.scene -s 1500x300 -j 1" "t_noise -s 1500" \
    "t_noise -s 9000x40"; do
    st=$(trap '' PIPE; $cmd -o - 2>err | head -c 100000 >/dev/null; echo "${PIPESTATUS[0]}")
    [ "$st" = 1 ] && grep -q "^t_[a-z]*: error: standard output: write error: Broken pipe$" err &&
        ok "${cmd%% *} to a reader that leaves early: exit 1, one line" ||
        notok "${cmd%% *} to a reader that leaves early" "exit $st: $(cat err)"
done
t_noise -s 9000x40 -o - >/dev/full 2>err
[ $? = 1 ] && grep -q '^t_noise: error: standard output: write error: No space' err &&
    ok "t_noise's rows of 36 KiB (writev) >/dev/full exit 1" ||
    notok "t_noise's wide rows >/dev/full exit 1" "$(cat err)"
t_noise -s 8 -o n.exr
t_info n.exr >/dev/full 2>err
[ $? = 1 ] && ok "t_info >/dev/full exits 1" || notok "t_info >/dev/full exits 1" "$(cat err)"
check "t_noise -V >/dev/null exits 0" t_noise -V
t_noise -V >&- 2>err && ok "t_noise -V with stdout closed: no write, exit 0" ||
    grep -q 'error: standard output' err && ok "t_noise -V with stdout closed: an error" ||
    notok "t_noise -V with stdout closed" "$(cat err)"

# --- 6: a terminal on standard input is refused at once ---
for cmd in "t_info" "t_palette marble -o x.png" "t_filter blur -o y.png" "t_convert -o z.png"; do
    # shellcheck disable=SC2086
    out=$(pty_run $cmd)
    if grep -q 'refusing to read image data from a terminal' <<<"$out" && grep -q '^exit 2' <<<"$out"; then
        ok "$cmd with a terminal on stdin: refused, exit 2"
    else
        notok "$cmd with a terminal on stdin: refused, exit 2" "$(tr '\r\n' '  ' <<<"$out" | head -c 200)"
    fi
done
[ ! -e x.png ] && [ ! -e y.png ] || notok "a refused read leaves no output file"

# --- 7: t_apply refuses a terminal on stdout before rendering ---
cat >slow.scene <<'S'
image 4000 4000
samples 16
camera { eye 0 0 -5 look 0 0 0 }
light { position 5 5 -5 }
object { sphere { radius 1 } }
S
t0=$(date +%s.%N)
out=$(pty_run t_apply slow.scene)
t1=$(date +%s.%N)
if grep -q 'refusing to write image data to a terminal' <<<"$out" && grep -q '^exit 2' <<<"$out" &&
    approx "$t1" "$t0" 3; then
    ok "t_apply with a terminal on stdout refuses before rendering"
else
    notok "t_apply with a terminal on stdout refuses before rendering" \
        "$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a " s"}'): $(tr '\r\n' '  ' <<<"$out" | head -c 200)"
fi
out=$(pty_run t_noise -s 16)
grep -q 'refusing to write image data to a terminal' <<<"$out" && grep -q '^exit 2' <<<"$out" &&
    ok "t_noise with a terminal on stdout: refused" || notok "t_noise with a terminal on stdout" "$out"

# --- 8: special output paths ---
mkfifo fifo.png
cat fifo.png >got.png &
rd=$!
timeout 20 t_noise -s 32 -o fifo.png
st=$?
wait "$rd"
if [ "$st" = 0 ] && [ -p fifo.png ] && [ "$(head -c 4 got.png | od -An -tx1 | tr -d ' ')" = 89504e47 ] &&
    [ "$(info_json got.png width)" = 32 ]; then
    ok "-o FIFO: written straight into it, the FIFO kept"
else
    notok "-o FIFO: written straight into it" "exit $st; $(ls -l fifo.png got.png)"
fi
compgen -G '.fifo.png.*' >/dev/null && notok "-o FIFO leaves no temporary file"
mkfifo fifo.pal
cat fifo.pal >got.pal &
rd=$!
timeout 20 t_palette --from '#000000' --to '#ffffff' -o fifo.pal
wait "$rd"
[ -p fifo.pal ] && grep -q . got.pal && ok "t_palette -o FIFO: written straight into it" ||
    notok "t_palette -o FIFO" "$(ls -l fifo.pal got.pal)"
mkdir -p real sub
t_noise -s 8 -o real/t.png
chmod 640 real/t.png
ln -s ../real/t.png sub/link.png
t_noise -s 24 -o sub/link.png
if [ -L sub/link.png ] && [ "$(readlink sub/link.png)" = ../real/t.png ] &&
    [ "$(info_json real/t.png width)" = 24 ] && [ "$(stat -c %a real/t.png)" = 640 ] &&
    [ -z "$(compgen -G 'real/.t.png.*')$(compgen -G 'sub/.*.XXX*')" ]; then
    ok "-o SYMLINK: the target replaced atomically, the link and the target's mode kept"
else
    notok "-o SYMLINK: the target replaced, the link kept" "$(ls -la sub real)"
fi
ln -s nowhere/new.png dangling.png
mkdir nowhere
t_noise -s 8 -o dangling.png
[ -L dangling.png ] && [ -f nowhere/new.png ] && ok "-o dangling SYMLINK: its target created" ||
    notok "-o dangling SYMLINK" "$(ls -la . nowhere)"
t_noise -s 8 -o n.png
ln -s n.png l2.png
t_palette --from '#000000' --to '#ff0000' -o pal.txt && ln -s pal.txt pal.link &&
    t_palette --from '#000000' --to '#00ff00' -o pal.link && [ -L pal.link ] &&
    grep -q . pal.txt && ok "t_palette -o SYMLINK keeps the link" || notok "t_palette -o SYMLINK keeps the link"

# --- 4: one policy for NaN and infinities in input maps (textura(5), --nonfinite) ---
export TEXTURA_PALETTES="$TEXTURA_TOP/palettes"
python3 - <<'PY'
import struct
def pfm(name, f, w=16, h=16):
    px = [f(x, y) for y in reversed(range(h)) for x in range(w)]  # PFM rows bottom-up
    open(name, "wb").write(b"Pf\n%d %d\n-1.0\n" % (w, h) + b"".join(struct.pack("<f", v) for v in px))
pfm("nan.pfm", lambda x, y: float("nan") if (x, y) in ((9, 6), (3, 12), (5, 13)) else 0.5)
pfm("inf.pfm", lambda x, y: float("-inf") if (x, y) == (2, 7) else 0.5)
pfm("allnan.pfm", lambda x, y: float("nan"))
pfm("half.pfm", lambda x, y: 0.25)
PY
# refused, exit 1, naming the file and the first pixel in reading order
refuses() {
    local name=$1 where=$2
    shift 2
    check_fails "$name: refused" 1 "$@"
    grep -q "$where" "$T/.err" || notok "$name: names the pixel" "$(cat "$T/.err")"
    if compgen -G 'out.*' >/dev/null; then notok "$name: no output" "$(ls out.*)"; rm -f out.*; fi
}
refuses "t_filter blur, 3 NaN pixels" 'nan.pfm: pixel (9,6) channel 0 is NaN' t_filter blur nan.pfm -o out.pfm
refuses "t_palette, an all-NaN map" 'allnan.pfm: pixel (0,0) channel 0 is NaN' t_palette marble allnan.pfm -o out.png
refuses "t_fft, NaN" 'pixel (9,6) channel 0 is NaN' t_fft nan.pfm -o out.exr
refuses "t_ifft, -inf" 'inf.pfm: pixel (2,7) channel 0 is -inf' t_ifft inf.pfm -o out.exr
refuses "t_sparse, -inf" 'pixel (2,7)' t_sparse -s 32 inf.pfm -o out.exr
refuses "t_op add, NaN second" 'nan.pfm: pixel (9,6)' t_op add half.pfm nan.pfm -o out.pfm
refuses "t_remap, NaN" 'pixel (9,6)' t_remap nan.pfm -o out.pfm
refuses "t_xform, NaN" 'pixel (9,6)' t_xform nan.pfm -o out.pfm
refuses "t_warp, NaN" 'pixel (9,6)' t_warp half.pfm nan.pfm -o out.pfm
refuses "t_tile, NaN" 'pixel (9,6)' t_tile nan.pfm -o out.pfm
refuses "t_convert, NaN" 'pixel (9,6)' t_convert nan.pfm -o out.exr
refuses "t_convert, NaN on standard input" 'standard input: pixel (9,6)' bash -c 't_convert -o out.exr <nan.pfm'
cat >nan.scene <<S
image 16 16
camera { eye 0 0 -3 look 0 0 0 fov 50 }
ambient 1 1 1
texture t file "$T/nan.pfm"
surface s { Ka 1 Kd 1 apply t { mapping planar Kd = f } }
box { min -1 -1 0 max 1 1 0.1 surface s }
S
check_fails "t_apply, a NaN texture: refused" 1 t_apply nan.scene -o out.exr
grep -q 'pixel (9,6)' "$T/.err" || notok "t_apply, a NaN texture: names the pixel" "$(cat "$T/.err")"
# --nonfinite V replaces them, keep keeps them; t_info counts them.
t_filter blur --nonfinite 0.5 nan.pfm -o blur.pfm && [ "$(info_json blur.pfm stats 0 nonfinite)" = 0 ] &&
    approx "$(info_json blur.pfm stats 0 min)" 0.5 1e-5 && ok "t_filter blur --nonfinite 0.5: finite, flat" ||
    notok "t_filter blur --nonfinite 0.5" "$(t_info blur.pfm 2>&1 | tail -1)"
t_filter blur --nonfinite keep nan.pfm -o keep.pfm && [ "$(info_json keep.pfm stats 0 nonfinite)" -gt 3 ] &&
    ok "t_filter blur --nonfinite keep spreads them as before" || notok "t_filter blur --nonfinite keep"
t_palette marble --nonfinite 0 allnan.pfm -o pal.png && ok "t_palette --nonfinite 0 colours the map" ||
    notok "t_palette --nonfinite 0"
t_apply --nonfinite 0.5 nan.scene -o nan.exr && [ "$(info_json nan.exr stats 0 nonfinite)" = 0 ] &&
    ok "t_apply --nonfinite 0.5 renders a finite image" || notok "t_apply --nonfinite 0.5"
[ "$(info_json nan.pfm stats 0 nonfinite)" = 3 ] && ok "t_info counts them (3)" || notok "t_info counts them"
check_fails "--nonfinite with a bad value" 2 t_filter blur --nonfinite nan nan.pfm -o out.pfm

# A full disk: every writer fails with one line and leaves nothing.  OIIO's
# BMP and TGA writers ignored a short write and exited 0 with a corrupt file.
mkdir -p "$T/full"
if mount -t tmpfs -o size=1m tmpfs "$T/full" 2>/dev/null; then
    for e in bmp tga exr pfm ppm; do
        check_fails "a full disk, .$e: refused" 1 t_noise -s 2048 -o "$T/full/x.$e"
        [ -z "$(ls -A "$T/full")" ] && ok "a full disk, .$e: nothing left" ||
            notok "a full disk, .$e: nothing left" "$(ls -A "$T/full")"
    done
    umount "$T/full"
else
    skip "a full disk" "cannot mount a tmpfs here (not root)"
fi

# ---- messages that said the wrong thing (issue 59, item 9) ----
# -s: 65536 a side for a map that streams; 2^30 pixels for one held whole, which a tool that
# holds it says (issue 58: a 65536^2 map passes a pipeline in bands).
check_fails "-s 65537: refused" 2 t_noise -s 65537 -o big.exr
grep -q "each side 1..65536" "$T/.err" && ok "-s 65537 says the side's limit" || notok "-s 65537's message" "$(cat "$T/.err")"
check_fails "midpoint -s 32769: refused" 2 t_fractal -m midpoint -s 32769 -o big.exr
grep -q "2^30" "$T/.err" && ok "midpoint -s 32769 says the 2^30-sample limit of a whole map" ||
    notok "midpoint -s 32769's message" "$(cat "$T/.err")"
check_fails "spectral -s 65536x16385: refused" 2 t_spectral -s 65536x16385 -o big.exr
grep -q "too large to hold whole" "$T/.err" && ok "spectral -s 65536x16385 says it holds the map whole" ||
    notok "spectral -s 65536x16385's message" "$(cat "$T/.err")"
check_fails "midpoint 40000x1000: refused" 2 t_fractal -m midpoint -s 40000x1000 -o big.exr
grep -q "each side at most 32768" "$T/.err" && ok "midpoint 40000x1000 says its lattice's limit" ||
    notok "midpoint 40000x1000's message" "$(cat "$T/.err")"
# the last rows of a 65536^2 map through three streaming stages (a window: the place is
# the full map's, the rows' offsets past 2^31 samples)
check "a window of a 65536^2 map streams" bash -c \
    't_noise -s 65536 --window 0,65516,65536,20 -f 8 | t_remap --gamma 2 | t_filter blur --sigma 2 | t_info > info.txt'
grep -q "65536x20, 1 channel" info.txt && ok "its rows pass whole" || notok "its rows pass whole" "$(head -3 info.txt)"
# A TIFF of 60,000 samples per pixel whose strip ends early: "truncated", at row 0 (libtiff
# said "Read error at scanline 4294967295").
python3 - <<'P'
import struct
w, h, spp = 4, 4, 60000
data = bytes(100)
tags = [(256, 3, w), (257, 3, h), (258, 3, 8), (259, 3, 1), (262, 3, 1), (273, 4, 8),
        (277, 3, spp), (278, 3, h), (279, 4, w * h * spp), (284, 3, 1)]
ifd = struct.pack('<H', len(tags)) + b''.join(
    struct.pack('<HHI', t, k, 1) + (struct.pack('<HH', v, 0) if k == 3 else struct.pack('<I', v))
    for t, k, v in tags) + struct.pack('<I', 0)
open('spp.tif', 'wb').write(b'II*\0' + struct.pack('<I', 8 + len(data)) + data + ifd)
P
check_fails "a TIFF of 60000 samples per pixel, cut short: refused" 1 t_info -q spp.tif
grep -q "truncated TIFF data at row 0" "$T/.err" && ! grep -q 4294967295 "$T/.err" &&
    ok "the TIFF of 60000 samples per pixel says truncated, at row 0" ||
    notok "the TIFF's message" "$(cat "$T/.err")"
# A truncated EXR says "truncated" as PNG, PNM and PFM do, from a file and on a pipe, in
# scanlines (plain and zip) and tiles, wherever it is cut.
t_noise -s 64 --compression none -o plain.exr && t_noise -s 64 -o zip.exr &&
    t_noise -s 64 --exr-tiles -o tiles.exr
bad=""
for f in plain zip tiles; do
    sz=$(stat -c %s $f.exr)
    for p in 20 50 90; do
        head -c $((sz * p / 100)) $f.exr >cut.exr
        t_info cut.exr >/dev/null 2>cut.err && bad="$bad $f-$p(read)"
        grep -q "truncated OpenEXR data" cut.err || bad="$bad $f-$p($(cat cut.err))"
        t_info - <cut.exr >/dev/null 2>cut.err
        grep -q "truncated OpenEXR data" cut.err || bad="$bad $f-$p-pipe($(cat cut.err))"
    done
done
[ -z "$bad" ] && ok "truncated EXRs (plain, zip, tiles; 20, 50, 90 %) say truncated" ||
    notok "truncated EXR messages" "${bad:0:300}"
# eye 0 1.5 inf: the third number is what is wrong, not the count.
printf 'camera { eye 0 1.5 inf look 0 0 0 }\nsphere { }\n' >inf.scene
check_fails "eye 0 1.5 inf: refused" 2 t_apply inf.scene -o inf.exr
grep -q "inf.scene:1:20: eye takes finite numbers (got inf)" "$T/.err" &&
    ok "eye 0 1.5 inf says the number is not finite, at it" || notok "eye inf's message" "$(cat "$T/.err")"
# t_info on a map of NaN alone: no figures of nothing, its NaN counted.
python3 -c "import struct, sys; sys.stdout.buffer.write(b'Pf\n8 8\n-1.0\n' + struct.pack('<64f', *[float('nan')] * 64))" >nan64.pfm
out=$(t_info nan64.pfm)
case $out in
*"min 0"*) notok "t_info on all NaN" "$out" ;;
*"no finite values: 64 NaN, 0 inf"*) ok "t_info on all NaN: no figures, 64 NaN" ;;
*) notok "t_info on all NaN" "$out" ;;
esac
[ "$(info_json nan64.pfm stats 0 nan)" = 64 ] && [ "$(info_json nan64.pfm stats 0 min)" = null ] &&
    ok "t_info --json on all NaN: nan 64, min null" || notok "t_info --json on all NaN" "$(t_info --json nan64.pfm)"
# t_assemble: a window's warning once (the first window was read twice).
oiiotool --create 8x4 5 --fullsize 8x8 -o w5a.exr 2>/dev/null &&
    oiiotool --create 8x4 5 --origin +0+4 --fullsize 8x8 -o w5b.exr 2>/dev/null
t_assemble w5a.exr w5b.exr -o w5.exr 2>w5.err
[ "$(grep -c "w5a.exr: 5 channels" w5.err)" = 1 ] && [ "$(grep -c "w5b.exr: 5 channels" w5.err)" = 1 ] &&
    ok "t_assemble warns of each window once" || notok "t_assemble's warnings" "$(cat w5.err)"
