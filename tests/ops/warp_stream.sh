#!/usr/bin/env bash
# warp_stream.sh - t_warp a band of rows at a time: BY spooled (or held when small) as its
# range is taken, then MAP through a window of rows bounded by the displacement's reach
# (spooled with --edge wrap, read down the stream with clamp): the whole map's bytes for
# any band height, -j, SIMD level, edge, --isotropic, --angle, -s and channels; a map far
# larger than the memory allowed; streams cut short; the one line of the fallback.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# MAPs of 1, 2 and 3 channels and odd sizes (no height a multiple of a band); BYs of
# another size, of 1, 2 and 3 channels, one of a narrow range (a window far from its row)
t_noise -s 301x203 -S 1 >y.exr
t_noise -s 301x203 -S 2 | t_palette marble >rgb.exr
t_filter gradient <y.exr >v2.exr
t_noise -s 173x211 -S 3 >by.exr
t_filter gradient <by.exr | t_remap --levels -6,6,-0.5,0.5 >by2.exr
t_remap --levels -1,1,0.9,1 <by.exr >near.exr
t_noise -s 640x700 -S 5 >tall.exr
# hard edges, where a footprint spans BY's whole range: taps far from the lookup's centre
t_checker -s 173x211 >chk.exr
t_checker -s 173x211 --ids >ids.exr
bad="" n=0
while read -r by args; do
    for src in y rgb v2; do
        [ "$src" = v2 ] && [ "$by" != by.exr ] && continue
        # the same command line, whose history the output keeps
        want=$(TEXTURA_BAND_ROWS=whole t_warp - $by $args <$src.exr 2>&1 | md5sum)
        n=$((n + 1))
        for rows in 1 7 64 ""; do
            got=$(cat $src.exr | TEXTURA_BAND_ROWS=$rows t_warp - $by $args 2>&1 | md5sum)
            [ "$got" = "$want" ] || bad+=" [$src $by $args /${rows:-default}]"
        done
        want=$(TEXTURA_BAND_ROWS=whole t_warp $src.exr - $args <$by 2>&1 | md5sum)
        got=$(cat $by | TEXTURA_BAND_ROWS=13 t_warp $src.exr - $args 2>&1 | md5sum)
        [ "$got" = "$want" ] || bad+=" [$src $by $args: BY on a pipe]"
    done
done <<'ARGS'
by.exr --displacement 0.05 --angle 90
by.exr --displacement 0.05 --angle 90 --edge clamp
by.exr --displacement 0.1
by.exr --displacement -0.07 --angle 30 --neutral 0.5 --edge clamp
by.exr --displacement 0.03 --isotropic
by.exr --displacement 0.03 --isotropic --edge clamp -s 517x333
by.exr --displacement 0.05 --angle 250 -s 64x400
by2.exr --displacement 0.05
by2.exr --displacement 0.05 --edge clamp -s 150x97
near.exr --displacement 0.3 --angle 270 --edge clamp
near.exr --displacement 0.3 --angle 90 --edge clamp
near.exr --displacement 0.3 --angle 90
near.exr --displacement -0.3 --angle 90 --isotropic
tall.exr --displacement 0.02 --angle 45 -s 120x90
chk.exr --displacement 0.05
chk.exr --displacement -0.04 --edge clamp -s 500x600
ids.exr --displacement 0.05 --angle 90 --neutral 1.5
ids.exr --displacement 0.05 --isotropic --neutral 1.5 --edge clamp
tall.exr --displacement 0.02 --isotropic --edge clamp -s 90x1000
ARGS
[ -z "$bad" ] && ok "t_warp: $n warps in bands give the whole map's bytes" ||
    notok "t_warp in bands" "$bad"
bad=""
for j in 1 3; do
    for simd in scalar ""; do
        for edge in wrap clamp; do
            got=$(cat rgb.exr | TEXTURA_SIMD=$simd TEXTURA_BAND_ROWS=9 t_warp -j $j - by.exr --displacement 0.04 --angle 60 --edge $edge | md5sum)
            [ "$got" = "$(TEXTURA_BAND_ROWS=whole t_warp - by.exr --displacement 0.04 --angle 60 --edge $edge <rgb.exr | md5sum)" ] ||
                bad+=" -j$j/${simd:-best}/$edge"
        done
    done
done
[ -z "$bad" ] && ok "and for -j 1 and 3, each SIMD level" || notok "t_warp with threads" "$bad"
TEXTURA_BAND_ROWS=whole t_warp rgb.exr by.exr --displacement 0.05 --angle 90 -o whole.png
TEXTURA_BAND_ROWS=5 t_warp rgb.exr by.exr --displacement 0.05 --angle 90 -o bands.png
cmp -s whole.png bands.png && ok "t_warp writes PNG in bands with the whole map's bytes" ||
    notok "t_warp to PNG in bands"

# Reaching (nearly) all of MAP, or BY not finite: MAP read whole, in one line (none with -q)
want=$(TEXTURA_BAND_ROWS=whole t_warp y.exr by.exr --displacement 0.7 --angle 90 | md5sum)
got=$(TEXTURA_BAND_ROWS=7 t_warp y.exr by.exr --displacement 0.7 --angle 90 2>err | md5sum)
[ "$got" = "$want" ] && [ "$(wc -l <err)" = 1 ] &&
    grep -qx "t_warp: warning: the displacement reaches [0-9]* of MAP's 203 rows: reading MAP whole" err &&
    ok "a reach near the whole map: MAP read whole, said in one line" ||
    notok "the fallback" "$(cat err)"
TEXTURA_BAND_ROWS=7 t_warp -q y.exr by.exr --displacement 0.7 --angle 90 2>err >/dev/null
[ ! -s err ] && ok "and -q says nothing" || notok "-q" "$(cat err)"
python3 -c '
import struct, sys
w, h = 31, 23
v = [((x * 7 + y * 3) % 11) / 11.0 for y in range(h) for x in range(w)]
v[100] = float("nan")
sys.stdout.buffer.write(b"Pf\n%d %d\n-1\n" % (w, h) + struct.pack("<%df" % len(v), *v))' >nan.pfm
want=$(TEXTURA_BAND_ROWS=whole t_warp --nonfinite keep y.exr nan.pfm | md5sum)
got=$(TEXTURA_BAND_ROWS=7 t_warp --nonfinite keep y.exr nan.pfm 2>err | md5sum)
[ "$got" = "$want" ] && grep -qx "t_warp: warning: BY is not finite: reading MAP whole" err &&
    ok "BY not finite (--nonfinite keep): MAP read whole, said in one line" ||
    notok "a BY not finite" "$(cat err)"

# Streams cut short: one line naming standard input, no output left, as BY (read before the
# output begins) and as MAP (spooled with wrap, read in bands with clamp)
head -c 150000 y.exr >cut.exr
truncated "BY cut short" out.exr TEXTURA_BAND_ROWS=7 t_warp rgb.exr -
truncated "MAP cut short, --edge wrap" out.exr TEXTURA_BAND_ROWS=7 t_warp - by.exr --angle 90
truncated "MAP cut short, --edge clamp" out.exr TEXTURA_BAND_ROWS=7 t_warp - by.exr --edge clamp
truncated "MAP cut short below the last window" out.exr TEXTURA_BAND_ROWS=7 t_warp - near.exr \
    --displacement 0.3 --angle 90 --edge clamp

# Bounded memory: a 4096x4096 RGB MAP (192 MiB as float; the whole-map path holds it, BY
# and the result, 448 MiB) warped by a small displacement under a limit far below it.  A
# sanitizer build has no limit to keep (its shadow memory): there the bytes alone, at 1024
lim=$(stream_vlimit 150000) side=$(stream_side 4096)
t_noise -s $side -f 8 -S 1 | t_palette --range 0,1 marble >big.exr
t_noise -s $side -f 4 -S 2 >bigby.exr
for args in "--angle 90" "--edge clamp --isotropic"; do
    want=$(TEXTURA_BAND_ROWS=whole t_warp - bigby.exr --displacement 0.05 $args <big.exr | md5sum)
    got=$(cat big.exr | (ulimit -v $lim; t_warp - bigby.exr --displacement 0.05 $args) | md5sum)
    [ "$got" = "$want" ] && ok "t_warp $args: a ${side}x$side stream under ulimit -v $lim KB" ||
        notok "t_warp $args under ulimit -v $lim" "$got vs $want"
done
