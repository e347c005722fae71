#!/usr/bin/env bash
# synth.sh - t_synth: quality against random crops, period, seams, determinism, mask,
# guide, channels, bad input.  Statistics come from tests/ops/synth_stats.py.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
stats() { python3 "$top/tests/ops/synth_stats.py" "$@"; }
lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

# A photo-like sample: bubbles through a palette (the recipe's sample).
t_bubble -s 128 -c 40 -S 3 | t_palette marble -o "$T/s.pfm"

# Quality: the mean distances over three seeds of the output's statistics from the
# sample's, beside three baselines of random 32x32 crops of the sample tiled together
# (synth_stats.py says how each is measured).  Measured when written: histogram 0.071
# against 0.083, radial power spectrum 0.150 against 0.230, gradient orientation
# 0.061 against 0.068.
for s in 1 2 3; do
    t_synth "$T/s.pfm" -s 256 -S "$s" -o "$T/o$s.pfm"
    stats crops "$T/s.pfm" 256 256 32 "$s" "$T/c$s.pfm"
done
stats dist "$T/s.pfm" "$T"/o[123].pfm >"$T/do"
stats dist "$T/s.pfm" "$T"/c[123].pfm >"$T/dc"
mean() { awk -v k="$2" '{ s += $k } END { printf "%.4f\n", s / NR }' "$1"; }
k=1
for what in "per-channel histogram" "radial power spectrum" "gradient-orientation histogram"; do
    o=$(mean "$T/do" $k) c=$(mean "$T/dc" $k)
    if lt "$o" "$c"; then ok "$what: output $o from the sample, closer than random crops ($c)"
    else notok "$what closer than random crops" "output $o, crops $c"; fi
    k=$((k + 1))
done

# Every output pixel is a pixel of the sample (the method copies positions).
r=$(python3 - "$T/s.pfm" "$T/o1.pfm" <<'PY'
import struct, sys
def px(p):
    d = open(p, 'rb').read().split(b'\n', 3)
    w, h = map(int, d[1].split())
    v = struct.unpack('<%df' % (3 * w * h), d[3][:12 * w * h])
    return {v[i:i + 3] for i in range(0, len(v), 3)}
print(px(sys.argv[2]) <= px(sys.argv[1]))
PY
)
[ "$r" = True ] && ok "every output pixel is a sample pixel" || notok "output pixels from the sample" "$r"

# A regular sample keeps its period: the highest autocorrelation of the output's luma
# between lags 24 and 40 is at 32 (+-1), the sample's period, along x and y.
t_checker -s 128 --nu 4 --nv 4 -o "$T/ck.pfm"
t_brick -s 128 -o "$T/br.pfm"
for s in ck br; do
    t_synth "$T/$s.pfm" -s 256 -o "$T/${s}o.pfm"
    read -r px py <<<"$(stats peak "$T/${s}o.pfm" 24 40)"
    if [ $((px > 32 ? px - 32 : 32 - px)) -le 1 ] && [ $((py > 32 ? py - 32 : 32 - py)) -le 1 ]; then
        ok "$s: the output keeps the period of 32 pixels (autocorrelation peaks at $px, $py)"
    else notok "$s keeps its period" "peaks at $px, $py"; fi
done

# --tile: the mean step across the wrap-around seams is no larger than the largest
# mean step between two inner columns or rows; without --tile it is (the test can fail).
for size in 200x160 201x157; do
    t_synth "$T/s.pfm" -s "$size" --tile -o "$T/t.pfm"
    read -r seam inner <<<"$(stats seam "$T/t.pfm")"
    if ! lt "$inner" "$seam"; then ok "--tile -s $size: seam step $seam, inner steps up to $inner"
    else notok "--tile -s $size: no seam" "seam $seam inner $inner"; fi
done
t_synth "$T/s.pfm" -s 200x160 -o "$T/nt.pfm"
read -r seam inner <<<"$(stats seam "$T/nt.pfm")"
if lt "$inner" "$seam"; then ok "without --tile the seams show ($seam against $inner)"
else notok "without --tile the seams show" "seam $seam inner $inner"; fi

# Determinism: the same bytes for -j 1 and -j 2, in every mode; seeds matter.  Samples
# of 64x64 (a run's fixed cost is the sample's pyramid and search index) and outputs of
# 72x60, several rows for each thread at every level; the exhaustive search, whose cost
# is the sample's size times the output's, from a sample of 48x40.
t_bubble -s 64 -c 12 -S 3 | t_palette marble -o "$T/s64.pfm"
t_noise -s 64x48 -f 4 -o "$T/n.pfm"
t_noise -s 48x40 -f 3 -o "$T/n_small.pfm"
t_noise -s 150x120 -f 2 -S 5 -o "$T/g.pfm"
t_noise -s 72x60 -f 2 -S 5 -o "$T/g_small.pfm"
t_circle -s 128 -r 0.2 --colour1 0,0,0 --colour2 1,1,1 -o "$T/mask.pfm"
t_circle -s 64 -r 0.2 --colour1 0,0,0 --colour2 1,1,1 -o "$T/mask64.pfm"
t_xform --expand 72x72 --background 0,0,0,0.5 "$T/s64.pfm" -o "$T/rgba.exr"
jcheck() {
    local name=$1
    shift
    t_synth "$@" -j 1 -o "$T/j1.pfm" && t_synth "$@" -j 2 -o "$T/j2.pfm" &&
        check "$name: -j 1 and -j 2 give the same bytes" cmp "$T/j1.pfm" "$T/j2.pfm" ||
        notok "$name: runs"
}
jcheck "RGB" "$T/s64.pfm" -s 72x60 -S 9
cp "$T/j1.pfm" "$T/seed9.pfm"
jcheck "one channel, --tile" "$T/n.pfm" -s 72x60 --tile
jcheck "--guide" "$T/s64.pfm" -s 72x60 --guide "$T/g_small.pfm"
jcheck "--mask" "$T/s64.pfm" --mask "$T/mask64.pfm"
jcheck "--search exhaustive" "$T/n_small.pfm" -s 40x30 --pyramid-levels 2 --search exhaustive
t_synth "$T/rgba.exr" -s 72x60 -j 1 -o "$T/a1.exr" && t_synth "$T/rgba.exr" -s 72x60 -j 2 -o "$T/a2.exr"
same "RGBA: -j 1 and -j 2 give the same map" "$T/a1.exr" "$T/a2.exr"
[ "$(info_json "$T/a1.exr" channels)" = 4 ] && ok "RGBA in, RGBA out" || notok "RGBA in, RGBA out"
[ "$(info_json "$T/j1.pfm" channels)" = 1 ] && ok "one channel in, one out" || notok "one channel"
t_synth "$T/s64.pfm" -s 72x60 -S 9 -o "$T/again.pfm"
t_synth "$T/s64.pfm" -s 72x60 -S 10 -o "$T/other.pfm"
check "the same seed gives the same bytes" cmp "$T/again.pfm" "$T/seed9.pfm"
if ! cmp -s "$T/again.pfm" "$T/other.pfm"; then ok "another seed, another map"; else notok "seeds matter"; fi

# --mask: pixels outside the mask are the sample's; none comes from inside it (the
# masked disc is painted magenta first: no magenta may survive).
python3 - "$T/s.pfm" "$T/mask.pfm" "$T/hole.pfm" <<'PY'
import struct, sys
d = open(sys.argv[1], 'rb').read().split(b'\n', 3)
w, h = map(int, d[1].split())
v = list(struct.unpack('<%df' % (3 * w * h), d[3][:12 * w * h]))
k = open(sys.argv[2], 'rb').read().split(b'\n', 3)
m = struct.unpack('<%df' % (3 * w * h), k[3][:12 * w * h])
for i in range(w * h):
    if m[3 * i] > 0.5:
        v[3 * i:3 * i + 3] = [1.0, 0.0, 1.0]
open(sys.argv[3], 'wb').write(b'PF\n%d %d\n-1.0\n' % (w, h) + struct.pack('<%df' % len(v), *v))
PY
t_synth "$T/hole.pfm" --mask "$T/mask.pfm" -o "$T/healed.pfm"
[ "$(stats same_outside "$T/hole.pfm" "$T/mask.pfm" "$T/healed.pfm")" = 1 ] &&
    ok "--mask keeps every unmasked pixel" || notok "--mask keeps every unmasked pixel"
r=$(python3 -c '
import struct, sys
d = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, d[1].split())
v = struct.unpack("<%df" % (3 * w * h), d[3][:12 * w * h])
print(sum(1 for i in range(w * h) if v[3 * i:3 * i + 3] == (1.0, 0.0, 1.0)))' "$T/healed.pfm")
[ "$r" = 0 ] && ok "--mask fills the hole from the rest (no masked pixel copied)" ||
    notok "--mask fills the hole from the rest" "$r magenta pixels"

# --guide: the output's luma follows the guide's.
t_synth "$T/s.pfm" -s 150x120 -o "$T/free.pfm"
t_synth "$T/s.pfm" -s 150x120 --guide "$T/g.pfm" -o "$T/guided.pfm"
cg=$(stats corr "$T/guided.pfm" "$T/g.pfm") cf=$(stats corr "$T/free.pfm" "$T/g.pfm")
if lt 0.4 "$cg" && lt "$(awk -v c="$cf" 'BEGIN { print c + 0.3 }')" "$cg"; then
    ok "--guide: correlation with the guide $cg (without it $cf)"
else notok "--guide is followed" "correlation $cg, without $cf"; fi

# Bad input: one line, exit 1 or 2, no output file.
t_noise -s 1 -o "$T/one.pfm"
t_noise -s 4 -o "$T/four.pfm"
printf 'Pf\n8 8\n-1.0\n' >"$T/nan.pfm"
python3 -c 'import struct, sys; sys.stdout.buffer.write(struct.pack("<64f", *([0.5] * 30 + [float("nan")] + [0.5] * 33)))' >>"$T/nan.pfm"
bad() {
    local name=$1 want=$2
    shift 2
    rm -f "$T/bad.pfm"
    check_fails "$name" "$want" t_synth "$@" -o "$T/bad.pfm"
    [ ! -e "$T/bad.pfm" ] && ok "$name: no output file" || notok "$name: no output file"
}
bad "a 1x1 sample" 1 "$T/one.pfm"
bad "a sample smaller than the neighbourhood" 1 "$T/four.pfm"
bad "NaN in the sample" 1 "$T/nan.pfm" -s 32
bad "an output over the size limit" 2 "$T/s.pfm" -s 20000
bad "an output over the map limit" 2 "$T/s.pfm" -s 70000
bad "a guide of another size" 2 "$T/s.pfm" -s 100 --guide "$T/g.pfm"
bad "a mask of another size" 2 "$T/s.pfm" --mask "$T/four.pfm"
bad "zero levels" 2 "$T/s.pfm" --pyramid-levels 0
bad "an even neighbourhood" 2 "$T/s.pfm" --neighbourhood 6
bad "a missing sample" 1 "$T/none.pfm"

# The recipe: a tileable map from a t_bubble | t_palette sample.
sh "$top/patterns/synth_tile.sh" -o "$T/recipe" -s 96 >/dev/null
t_convert "$T/recipe_tile.exr" -o "$T/recipe.pfm"
[ "$(info_json "$T/recipe.pfm" width)x$(info_json "$T/recipe.pfm" height)" = 96x96 ] &&
    ok "patterns/synth_tile.sh writes the map" || notok "patterns/synth_tile.sh writes the map"
read -r seam inner <<<"$(stats seam "$T/recipe.pfm")"
if [ -n "$seam" ] && [ -n "$inner" ] && ! lt "$inner" "$seam"; then
    ok "patterns/synth_tile.sh: the map tiles (seam $seam, inner $inner)"
else notok "patterns/synth_tile.sh: the map tiles" "seam $seam inner $inner"; fi

# A mask over the whole sample leaves nothing to copy from.
t_circle -s 128 -r 0.1 --colour1 1,1,1 --colour2 1,1,1 -o "$T/all.pfm"
bad "a mask over the whole sample" 1 "$T/s.pfm" --mask "$T/all.pfm"

# Values whose squared distances overflow: 1e20 made FLANN hand back no
# neighbour (index -1, SIGSEGV), 3e38 everywhere made every quilting cost NaN
# (a division by zero candidates, SIGFPE).  Both synthesise, from a file and
# from standard input, and keep the sample's range.
t_noise -s 64 -f 64 | t_op mul - 1e20 >"$T/e20.exr"
t_noise -s 64 | t_op mul - 0 | t_op add - 3e38 >"$T/e38.exr"
for m in e20 e38; do
    check "t_synth, a sample of $m: from a file" t_synth -s 32 "$T/$m.exr" -o "$T/$m-f.exr"
    check "t_synth, a sample of $m: from standard input" \
        sh -c "t_synth -s 32 - -o '$T/$m-s.exr' <'$T/$m.exr'"
done
approx "$(info_json "$T/e38-f.exr" stats 0 min)" 3e38 1e32 && approx "$(info_json "$T/e38-s.exr" stats 0 max)" 3e38 1e32 &&
    ok "t_synth, a sample of 3e38: 3e38 everywhere" ||
    notok "t_synth, a sample of 3e38" "$(t_info "$T/e38-f.exr" | sed -n 2p)"
approx "$(info_json "$T/e20-f.exr" stats 0 min)" 2e19 2e19 && ok "t_synth, a sample of 1e20: in its range" ||
    notok "t_synth, a sample of 1e20: in its range" "$(t_info "$T/e20-f.exr" | sed -n 2p)"
