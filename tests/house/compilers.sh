# compilers.sh - the same maps, byte for byte, from every build of the suite
#
# make test builds the tools three ways (gcc -O2, gcc -O1 with ASan and UBSan,
# clang -O2).  Floating-point contraction is off everywhere (base/fp_strict.h,
# -ffp-contract=off), so each build's generators must write the very bytes of
# the plain gcc build's.  Runs only where that build exists beside this one.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
ref=$top/build/bin
[ "$(cd "$TEXTURA_BUILD" && pwd)" != "$top/build" ] && [ -x "$ref/t_noise" ] || exit 0
cc=$(sed -n 's/^CC = //p' "$TEXTURA_BUILD/config.mk" 2>/dev/null)
mkdir -p "$T/a" "$T/b"
while IFS= read -r cmd; do
    [ -n "$cmd" ] || continue
    cmd2=${cmd//SCENES/$top/tests/scenes}
    set -- ${cmd2//GOLDEN/$top/tests/golden}
    tool=$1
    shift
    # the same -o: the history line is part of the bytes
    (cd "$T/a" && "$ref/$tool" "$@" -o map.exr 2>/dev/null)
    (cd "$T/b" && "$tool" "$@" -o map.exr 2>"$T/err")
    cmp -s "$T/a/map.exr" "$T/b/map.exr" \
        && ok "$cmd: the same bytes as gcc's plain build (${cc:-cc})" \
        || notok "$cmd: differs from gcc's plain build (${cc:-cc})" "$(head -c 200 "$T/err")"
done <<'LIST'
t_noise -s 96 -f 37 -S 3
t_noise -s 64 -f 9 --z 0.37 --fade quintic
t_turbulence -s 96 -S 5
t_fractal -s 96 --mode fbm
t_fractal -s 96 --mode ridged
t_fractal -s 96 --mode hybrid
t_fractal -s 64 --mode midpoint
t_bubble -s 96 -c 300 --value f2-f1
t_holes -s 64
t_colorvar -s 64
t_perturb -s 64
t_spectral -s 64
t_d_noise -s 64 --normal
t_apply SCENES/spheres.scene -s 80x60
t_synth GOLDEN/thesis_turbulence_stripe.exr -s 72x56 --tile
LIST
