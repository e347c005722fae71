#!/usr/bin/env bash
# lockstep.sh - t_op and t_cascade read their maps a band of rows at a time, in lockstep
# (cli/lockstep.h), and write each band of the result as it passes: the whole map's bytes
# for every operator and band height, two pipes at once, and a map of any size in bounded
# memory.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# Odd sizes, no multiple of a band: one channel and RGB
t_noise -s 301x203 -S 1 >a.exr
t_noise -s 301x203 -S 2 | t_palette marble >b.exr
t_noise -s 301x203 -S 3 >w.exr

# every operator, from t_op's help; its arity found by asking (a usage error names it)
ops=$(t_op --help | sed -n '2p' | sed 's/.*pixel: //; s/;.*//; s/(Porter-Duff)//; s/,/ /g')
[ "$(wc -w <<<"$ops")" -ge 15 ] && ok "t_op lists its operators ($(wc -w <<<"$ops"))" || notok "t_op's operators" "$ops"
bad="" n=0
for op in $ops; do
    for operands in "- b.exr w.exr" "- a.exr w.exr" "b.exr - w.exr"; do
        set -- $operands
        args=""
        for k in 1 2 3; do
            args=$(echo $operands | cut -d' ' -f1-$k)
            t_op $op $args <a.exr >/dev/null 2>&1 && break
            args=""
        done
        [ -n "$args" ] || continue
        # the whole map's bytes (TEXTURA_BAND_ROWS=whole)
        want=$(TEXTURA_BAND_ROWS=whole t_op $op $args <a.exr | md5sum)
        n=$((n + 1))
        for rows in "" 1 7 64; do
            got=$(cat a.exr | TEXTURA_BAND_ROWS=$rows t_op $op $args | md5sum)
            [ "$got" = "$want" ] || bad+=" $op($args)/${rows:-default}"
        done
    done
done
[ "$n" -ge 40 ] && [ -z "$bad" ] && ok "t_op: $n operations in lockstep give the whole map's bytes" ||
    notok "t_op in lockstep ($n operations)" "$bad"
# with threads: the same bytes for any -j
want=$(TEXTURA_BAND_ROWS=whole t_op mix - b.exr w.exr <a.exr | md5sum)
for j in 1 2 3; do
    [ "$(cat a.exr | t_op -j $j mix - b.exr w.exr | md5sum)" = "$want" ] || bad+=" -j$j"
done
[ -z "$bad" ] && ok "and for -j 1, 2, 3" || notok "t_op lockstep with threads" "$bad"

# two pipes at once, and a constant beside them
same "t_op add <(a) <(b): two pipes in lockstep" <(t_op add <(cat a.exr) <(cat b.exr)) <(TEXTURA_BAND_ROWS=whole t_op add - b.exr <a.exr)
same "t_op mix <(a) 0.5,0.2,0.1 <(w)" <(t_op mix <(cat a.exr) 0.5,0.2,0.1 <(cat w.exr)) <(TEXTURA_BAND_ROWS=whole t_op mix - 0.5,0.2,0.1 w.exr <a.exr)
# standard output redirected to a file: the uncompressed stream, as the whole map's writer
# sends it (the first streaming tools compress it there; these keep their bytes)
TEXTURA_BAND_ROWS=whole t_op add - b.exr <a.exr >whole.exr
cat a.exr | t_op add - b.exr >bands.exr
cmp -s whole.exr bands.exr && ok "t_op > FILE: the whole map's bytes" || notok "t_op > FILE differs"
# to other formats in bands too
TEXTURA_BAND_ROWS=whole t_op add - b.exr -o whole.png <a.exr
cat a.exr | t_op add - b.exr -o bands.png
cmp -s whole.png bands.png && ok "t_op writes PNG in bands with the whole map's bytes" || notok "t_op to PNG in bands"
# operands of other sizes are read whole and fitted, as before
t_noise -s 100 >small.exr
check_fails "an operand of another size: the whole map's usage error" 2 bash -c "cat a.exr | t_op add - small.exr"
grep -q "small.exr is 100x100 but the result is 301x203" "$T/.err" || notok "the size message" "$(cat "$T/.err")"
[ "$(cat a.exr | t_op add - small.exr --resize tile | md5sum)" = "$(TEXTURA_BAND_ROWS=whole t_op add - small.exr --resize tile <a.exr | md5sum)" ] &&
    ok "--resize tile: the whole map's bytes" || notok "--resize tile"

# a stream cut short: one line naming standard input, nothing left behind
head -c 100000 a.exr >cut.exr
truncated "a truncated operand" out.exr t_op add - b.exr

# Bounded memory: two 4096x4096 generators (64 MiB each as float, 192 MiB with the result
# whole) added under a limit far below them
lim=$(stream_vlimit 120000) side=$(stream_side 4096)
want=$(t_op add <(t_noise -s $side -f 8 -S 1) <(t_noise -s $side -f 8 -S 2) | md5sum)
got=$( (ulimit -v $lim; t_op add <(t_noise -s $side -f 8 -S 1) <(t_noise -s $side -f 8 -S 2)) | md5sum)
[ "$got" = "$want" ] && ok "t_op adds two ${side}x$side streams under ulimit -v $lim KB" ||
    notok "t_op under ulimit -v $lim" "$got vs $want"

# t_cascade: the ids and the regions' maps in lockstep
t_circle -s 301x203 --ids -o ids.exr
t_op threshold a.exr | t_op add - 1 >ids2.exr
bad="" n=0
while read -r in args; do
    want=$(TEXTURA_BAND_ROWS=whole t_cascade $args <$in 2>&1 | md5sum)
    n=$((n + 1))
    for rows in "" 1 7 64; do
        got=$(cat $in | TEXTURA_BAND_ROWS=$rows t_cascade $args 2>&1 | md5sum)
        [ "$got" = "$want" ] || bad+=" [$args/${rows:-default}]"
    done
done <<'ARGS'
b.exr ids.exr 1=-
b.exr --regions 2 ids2.exr 1=a.exr 2=-
ids2.exr --regions 2 - 1=a.exr 2=b.exr
a.exr --regions 2 ids2.exr 2=- --default #ff000080
a.exr ids.exr 1=- 2=b.exr
a.exr --regions 2 ids2.exr 1=- 2=small.exr --resize tile
ARGS
[ -z "$bad" ] && ok "t_cascade: $n cascades in lockstep give the whole map's bytes" || notok "t_cascade in lockstep" "$bad"
want=$(t_cascade <(t_circle -s $side --ids) 1=<(t_noise -s $side -f 8) | md5sum)
got=$( (ulimit -v $lim; t_cascade <(t_circle -s $side --ids) 1=<(t_noise -s $side -f 8)) | md5sum)
[ "$got" = "$want" ] && ok "t_cascade fills a ${side}x$side stream under ulimit -v $lim KB" ||
    notok "t_cascade under ulimit -v $lim" "$got vs $want"
