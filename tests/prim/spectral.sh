# tests/prim/spectral.sh - t_fft, t_ifft, t_spectral, t_sparse from the command line
. "$(dirname "$0")/../lib.sh"

# pfm W H PYEXPR FILE: a 1-channel PFM whose pixel (x,y), y from the top, is PYEXPR
pfm() {
    python3 - "$@" <<'EOF'
import math, struct, sys
w, h, expr, path = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
with open(path, 'wb') as f:
    f.write(b"Pf\n%d %d\n-1.0\n" % (w, h))
    for y in range(h - 1, -1, -1):  # PFM rows go bottom to top
        f.write(struct.pack('<%df' % w, *[float(eval(expr)) for x in range(w)]))
EOF
}

# pfm_cmp A B EXPR: read two PFMs, print max over pixels of EXPR(a, b, x, y, w, h)
pfm_eval() {
    python3 - "$@" <<'EOF'
import math, struct, sys
def read(path):
    d = open(path, 'rb').read()
    parts = d.split(b"\n", 3)
    nc = 3 if parts[0] == b"PF" else 1
    w, h = map(int, parts[1].split())
    v = struct.unpack('<%df' % (w * h * nc), parts[3][:w * h * nc * 4])
    rows = [v[(h - 1 - y) * w * nc:(h - y) * w * nc] for y in range(h)]
    return w, h, [p for r in rows for p in r[::nc]]
w, h, a = read(sys.argv[1])
_, _, b = read(sys.argv[2]) if sys.argv[2] != '-' else (w, h, a)
print(max(eval(sys.argv[3]) for i, (A, B) in enumerate(zip(a, b)) for x, y in [(i % w, i // w)]))
EOF
}

lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

# --- t_fft | t_ifft gives the input back
t_noise -s 96x64 -S 3 -o "$T/a.pfm"
t_fft --as complex "$T/a.pfm" | t_ifft -o "$T/b.pfm"
d=$(pfm_eval "$T/a.pfm" "$T/b.pfm" 'abs(A - B)')
if lt "$d" 1e-5; then ok "t_fft --as complex | t_ifft reproduces the map (max error $d)"
else notok "t_fft | t_ifft roundtrip" "max error $d"; fi
t_fft --as mag -o "$T/mag.exr" "$T/a.pfm"
t_fft --as phase -o "$T/ph.exr" "$T/a.pfm"
t_ifft --phase "$T/ph.exr" --rescale none -o "$T/c.pfm" "$T/mag.exr"
d=$(pfm_eval "$T/a.pfm" "$T/c.pfm" 'abs(A - B)')
if lt "$d" 1e-4; then ok "t_fft --as mag and --as phase, inverted with --phase MAP (max error $d)"
else notok "mag + phase roundtrip" "max error $d"; fi
check "t_fft --window-function hann writes a log spectrum" t_fft --window-function hann -o "$T/w.exr" "$T/a.pfm"
if approx "$(info_json "$T/w.exr" stats 0 max)" 1 1e-6; then ok "log magnitude peaks at 1"
else notok "log magnitude peaks at 1"; fi

# --- one painted frequency: a cosine of the right period and orientation
pfm 64 48 '1.0 if (x, y) == (32 + 4, 24 - 3) else 0.0' "$T/one.pfm"
t_ifft --symmetric --phase zero -o "$T/cos.pfm" "$T/one.pfm"
d=$(pfm_eval "$T/cos.pfm" - 'abs(A - (0.5 + 0.5 * math.cos(2 * math.pi * (4 * x / w - 3 * y / h))))')
if lt "$d" 1e-4; then ok "a painted frequency (4,-3) gives cos(2 pi (4x/w - 3y/h)) (error $d)"
else notok "single painted frequency" "max error $d"; fi

# --- --symmetric makes a real texture
pfm 40 40 'math.exp(-((x - 20) ** 2 + (y - 20) ** 2) / 30.0) if y < 20 else 0.0' "$T/half.pfm"
t_ifft --symmetric --as complex -S 4 -o "$T/sym.exr" "$T/half.pfm"
if [ "$(info_json "$T/sym.exr" stats 1 max)" = 0 ] && [ "$(info_json "$T/sym.exr" stats 1 min)" = 0 ]
then ok "--symmetric output has a zero imaginary part"; else notok "--symmetric imaginary part"; fi
t_ifft -S 4 --as complex -o "$T/asym.exr" "$T/half.pfm"
if lt 0.01 "$(info_json "$T/asym.exr" stats 1 stddev)"; then
    ok "without --symmetric a half-painted spectrum has an imaginary part"
else notok "without --symmetric imaginary part"; fi

# --- determinism: same seed, any thread count, same pixels; another seed differs
for cmd in "t_spectral -s 200x120 --anisotropy 30,2" "t_ifft --symmetric $T/half.pfm" \
           "t_ifft $T/half.pfm" "t_fft --window-function hann $T/a.pfm" "t_sparse -s 100 $T/a.pfm"; do
    set -- $cmd
    tool=$1
    shift
    case $tool in t_fft) seed= ;; *) seed="-S 9" ;; esac
    $tool -j 1 $seed -o "$T/j1.pfm" "$@" && $tool -j 2 $seed -o "$T/j2.pfm" "$@"
    if cmp -s "$T/j1.pfm" "$T/j2.pfm"; then ok "$tool: -j 1 and -j 2 give the same bytes"
    else notok "$tool: -j 1 and -j 2 differ"; fi
done
t_spectral -s 64 -S 1 -o "$T/s1.pfm"
t_spectral -s 64 -S 2 -o "$T/s2.pfm"
if ! cmp -s "$T/s1.pfm" "$T/s2.pfm"; then ok "t_spectral: another seed, another map"
else notok "t_spectral ignores the seed"; fi
check "t_spectral -D 2.2 is t_spectral --h 0.8" bash -c \
    "t_spectral -s 64 -D 2.2 -o '$T/d.pfm' && t_spectral -s 64 --h 0.8 -o '$T/h.pfm' && cmp '$T/d.pfm' '$T/h.pfm'"
t_spectral -s 64x40 -o "$T/t.pfm"
seam=$(pfm_eval "$T/t.pfm" - 'abs(A - a[y * w + (x + 1) % w]) if x == w - 1 else 0')
inner=$(pfm_eval "$T/t.pfm" - 'abs(A - a[y * w + x + 1]) if x == w // 2 else 0')
if lt "$seam" "$(awk -v i="$inner" 'BEGIN { print 3 * i }')"; then
    ok "t_spectral tiles (largest seam step $seam, inner $inner)"
else notok "t_spectral tiles" "seam $seam inner $inner"; fi

# --- bad input: a message naming the tool, exit 1 or 2
pfm 32 32 '0.5' "$T/ph32.pfm"
pfm 40 40 '0.0' "$T/zero.pfm"
pfm 40 40 'float("nan") if (x, y) == (3, 2) else 1.0' "$T/nan.pfm"
pfm 40 40 'float("inf") if (x, y) == (3, 2) else 0.5' "$T/inf.pfm"
printf 'Pf\n0 0\n-1.0\n' >"$T/empty.pfm"
check_fails "t_ifft: phase map of another size" 1 t_ifft --phase "$T/ph32.pfm" "$T/half.pfm"
check_fails "t_ifft: all-zero spectrum" 1 t_ifft "$T/zero.pfm"
check_fails "t_ifft: NaN in the spectrum" 1 t_ifft "$T/nan.pfm"
check_fails "t_ifft: infinity in the phase map" 1 t_ifft --phase "$T/inf.pfm" "$T/half.pfm"
check_fails "t_ifft: zero-size spectrum" 2 t_ifft "$T/empty.pfm"
check_fails "t_fft: NaN in the map" 1 t_fft "$T/nan.pfm"
check_fails "t_fft: zero-size map" 2 t_fft "$T/empty.pfm"
check_fails "t_sparse: infinity in the sample" 1 t_sparse -s 64 "$T/inf.pfm"
check_fails "t_ifft: --phase with a complex spectrum" 2 t_ifft --phase zero "$T/sym.exr"
check_fails "t_ifft: --phase - with the spectrum on standard input" 2 t_ifft --phase -
check_fails "t_ifft: bad --as" 2 t_ifft --as imag "$T/half.pfm"
check_fails "t_spectral: --fractal-dimension below 2" 2 t_spectral --fractal-dimension 1.5
check_fails "t_spectral: --band LO > HI" 2 t_spectral --band 5,2
check_fails "t_spectral: --band with no frequency" 2 t_spectral -s 16 --band 500,600
check_fails "t_spectral: --anisotropy ratio 0" 2 t_spectral --anisotropy 30,0
check_fails "t_sparse: sample larger than the map" 2 t_sparse -s 16 "$T/half.pfm"
man=$("$TEXTURA_TOP/tests/mkman" "$TEXTURA_BUILD/bin" --check 2>&1)
for t in t_fft t_ifft t_spectral t_sparse; do
    if grep -q "^ok - man/man1/$t.1 " <<<"$man"; then ok "man/man1/$t.1 lists the options of $t"
    else notok "man/man1/$t.1 lists the options of $t (missing, or run make man)"; fi
done

# The transforms keep the history of the map they came from.
t_noise -s 32 -S 9 | t_fft --as complex | t_ifft | t_info >"$T/hist.txt"
check "t_fft | t_ifft keeps the history and adds both stages" \
    grep -qzE 't_noise -s 32 -S 9.*t_fft --as complex.*t_ifft' "$T/hist.txt"
t_noise -s 16 | t_sparse -s 32 | t_info >"$T/hist2.txt"
check "t_sparse keeps the history of its sample" grep -qzE 't_noise -s 16.*t_sparse -s 32' "$T/hist2.txt"
