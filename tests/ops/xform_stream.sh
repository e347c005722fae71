#!/usr/bin/env bash
# xform_stream.sh - t_xform's expand, whole-pixel shift (with and without --wrap) and clip
# go a band of rows at a time, and so do rotate (up to 90 degrees either way), scale and
# fractional shifts, each step keeping the rows the next reads: the whole map's bytes for
# any band height and -j, the same usage errors, a map of any size in bounded memory.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# odd sizes, one channel and RGB
t_noise -s 301x203 -S 1 >y.exr
t_noise -s 301x203 -S 2 | t_palette marble >rgb.exr
bad="" n=0
while read -r args; do
    for src in y rgb; do
        # the whole map's bytes and messages (TEXTURA_BAND_ROWS=whole)
        want=$(TEXTURA_BAND_ROWS=whole t_xform $args <$src.exr 2>&1 | md5sum)
        n=$((n + 1))
        rowset="1 64" # and the default below
        [ "$src" = y ] && rowset="7"
        for rows in $rowset ""; do
            got=$(cat $src.exr | TEXTURA_BAND_ROWS=$rows t_xform $args 2>&1 | md5sum)
            [ "$got" = "$want" ] || bad+=" [$src $args /${rows:-default}]"
        done
    done
done <<'ARGS'
--shift 10,20
--shift -7,-33
--shift -7,-33 --wrap
--shift 75,50 --wrap
--shift 3,1000 --wrap
--shift 3,1000
--shift 0,0 --wrap
--expand 250x100 --shift 5,-30 --wrap
--expand 400x300 --shift 0,60 --wrap
--expand 400x300 --shift 0,-20 --wrap
--expand 400x300 --shift 0,-280 --wrap
--clip 0,50,301,120 --shift 0,30 --wrap
--clip 0,150,301,203 --shift 9,-40 --wrap
--clip 10,20,200,150
--clip 0,0,301,203
--expand 400x300
--expand 250x100
--expand 400x300 --background #ff000080
--expand 400x301 --shift 13,-17 --clip 5,5,300,290
--expand 400x300 --shift 20,30 --wrap --background #00ff0080
--shift 2.5,1
--rotate 30 --shift 4,4
--scale 0.5 --clip 0,0,100,100
--rotate 30
--rotate -20 --around 50,60
--rotate 89.5
--rotate 120
--scale 0.37,1.7
--scale 2.5
--scale 0.02
--shift 0.5,0 --wrap
--shift 0.5,0.25 --wrap
--rotate 30 --background #ff000080
--expand 400x300 --rotate 15 --scale 0.8 --shift 3.3,-2.1 --clip 10,20,300,200
ARGS
[ -z "$bad" ] && ok "t_xform: $n chains from a stream give the whole map's bytes" ||
    notok "t_xform streamed" "$bad"
for j in 1 3; do
    [ "$(cat rgb.exr | t_xform -j $j --shift 5,9 --wrap | md5sum)" = "$(TEXTURA_BAND_ROWS=whole t_xform --shift 5,9 --wrap <rgb.exr | md5sum)" ] ||
        bad+=" -j$j"
done
[ -z "$bad" ] && ok "and for -j 1 and 3" || notok "t_xform with threads" "$bad"
check_fails "a clip outside the map: the whole map's usage error" 2 bash -c "cat y.exr | t_xform --clip 0,0,400,100"
grep -q "clip window 0,0 to 400,100 must lie inside the 301x203 map" "$T/.err" || notok "the clip message" "$(cat "$T/.err")"
# standard output redirected to a file: the uncompressed stream, as before
TEXTURA_BAND_ROWS=whole t_xform --shift 5,9 <rgb.exr >whole.exr
cat rgb.exr | t_xform --shift 5,9 >bands.exr
cmp -s whole.exr bands.exr && ok "t_xform > FILE: the whole map's bytes" || notok "t_xform > FILE differs"
# to PNG in bands too
TEXTURA_BAND_ROWS=whole t_xform --expand 320x240 --shift 5,5 -o whole.png <rgb.exr
cat rgb.exr | t_xform --expand 320x240 --shift 5,5 -o bands.png
cmp -s whole.png bands.png && ok "t_xform writes PNG in bands with the whole map's bytes" || notok "t_xform to PNG in bands"
# a stream cut short: one line naming standard input, nothing left
head -c 100000 y.exr >cut.exr
truncated "a truncated stream" out.exr t_xform --shift 3,3
# with a vertical wrap: cut among the rows spooled (from row 153), and among those that
# stream on after a spool of rows 0..52
truncated "a truncated stream while spooling" out.exr t_xform --shift 3,50 --wrap
truncated "a truncated stream after the spool" out.exr t_xform --shift 3,150 --wrap

# Bounded memory: a 4096x4096 RGB map (192 MiB as float) expanded, shifted with a wrap
# (spooled to TMPDIR) and clipped, under a limit far below it
lim=$(stream_vlimit 180000) side=$(stream_side 4096)
t_noise -s $side -f 8 | t_palette --range 0,1 marble >big.exr
q=$((side / 4)) # at 4096: --expand 4200x4100 --shift 1024,-1030 --clip 8,8,4000,4000
for args in "--expand $((side + 104))x$((side + 4)) --shift $q,-$((q + 6)) --wrap --clip 8,8,$((side - 96)),$((side - 96))" \
    "--rotate 5" "--scale 0.5" "--shift 10.5,7.25"; do
    want=$(TEXTURA_BAND_ROWS=whole t_xform $args <big.exr | md5sum)
    got=$(cat big.exr | (ulimit -v $lim; t_xform $args) | md5sum)
    [ "$got" = "$want" ] && ok "t_xform $args: a ${side}x$side stream under ulimit -v $lim KB" ||
        notok "t_xform $args under ulimit -v $lim" "$got vs $want"
done
