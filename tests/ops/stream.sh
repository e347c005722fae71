# stream.sh - the tools that stream give the whole-map path's bytes, in bounded memory,
# and start writing before their input has ended
. "$(dirname "$0")/../lib.sh"

# Maps of odd sizes, whose height is no multiple of any band: one channel and RGB
t_noise -s 301x203 -S 3 >"$T/y.exr"
t_noise -s 301x203 -S 4 | t_palette marble >"$T/rgb.exr"

# every operation of t_filter, from its --help: the stream (a pipe, bands of 1, 7, 64 rows
# and the default) against the whole map (TEXTURA_BAND_ROWS=whole)
ops=$(t_filter --help | awk '/^filter a texture map/ { f = 1; next } f && /^  [a-z]/ { print $1 } f && !/^  / { exit }')
[ "$(wc -w <<<"$ops")" -ge 11 ] && ok "t_filter lists its operations ($(wc -w <<<"$ops"))" ||
    notok "t_filter's operations" "$ops"
for op in $ops; do
    for edge in clamp mirror wrap; do
        e="--edge $edge"
        [ "$op" = noise ] && { [ "$edge" = clamp ] || continue; e=""; }
        bad=""
        for src in y rgb; do
            want=$(TEXTURA_BAND_ROWS=whole t_filter "$op" $e <"$T/$src.exr" | md5sum)
            for rows in "" 1 7 64; do
                got=$(cat "$T/$src.exr" | TEXTURA_BAND_ROWS=$rows t_filter "$op" $e | md5sum)
                [ "$got" = "$want" ] || bad+=" $src/${rows:-default}"
            done
        done
        [ -z "$bad" ] && ok "t_filter $op --edge $edge: a stream gives the whole map's bytes" ||
            notok "t_filter $op --edge $edge streamed" "differs for$bad"
    done
done
# from a file operand, read a band at a time: the same pixels as the whole map
TEXTURA_BAND_ROWS=whole t_filter blur --sigma 1.5 <"$T/rgb.exr" >"$T/whole.exr"
TEXTURA_BAND_ROWS=5 t_filter blur --sigma 1.5 "$T/rgb.exr" -o "$T/bands.exr"
same "t_filter reads a file operand in bands, with the same pixels" "$T/whole.exr" "$T/bands.exr"
check_fails "TEXTURA_BAND_ROWS out of range" 2 bash -c "TEXTURA_BAND_ROWS=0 t_filter blur '$T/y.exr'"

# t_info: the figures of a stream are those of the same map from a file
bad=""
for src in y rgb whole; do
    for j in "" --json; do
        [ "$(TEXTURA_BAND_ROWS=whole t_info $j <"$T/$src.exr")" = "$(cat "$T/$src.exr" | t_info $j)" ] &&
            [ "$(TEXTURA_BAND_ROWS=whole t_info $j <"$T/$src.exr")" = "$(t_info $j <"$T/$src.exr")" ] ||
            bad+=" $src$j"
    done
done
[ -z "$bad" ] && ok "t_info gives a stream's figures, the same as a file's" ||
    notok "t_info streamed" "differs for$bad"

# t_palette's auto range from a stream: spooled, then coloured a band at a time
bad=""
for pal in marble greys; do
    for rows in "" 7; do
        [ "$(TEXTURA_BAND_ROWS=whole t_palette $pal <"$T/y.exr" | md5sum)" = "$(cat "$T/y.exr" | TEXTURA_BAND_ROWS=$rows t_palette $pal | md5sum)" ] ||
            bad+=" $pal/${rows:-default}"
    done
done
[ -z "$bad" ] && ok "t_palette's auto range from a stream gives the whole map's bytes" ||
    notok "t_palette auto range streamed" "differs for$bad"

# Bounded memory: a 4096x4096 RGB map (192 MiB, three times that for the whole-map blur)
# through t_filter under a limit below the map's size
lim=$(stream_vlimit 180000) side=$(stream_side 4096)
t_noise -s $side -f 8 | t_palette --range 0,1 marble >"$T/big.exr"
want=$(TEXTURA_BAND_ROWS=whole t_filter blur --sigma 2 <"$T/big.exr" | md5sum)
got=$(cat "$T/big.exr" | (ulimit -v $lim; t_filter blur --sigma 2) | md5sum)
[ "$got" = "$want" ] && ok "t_filter blur streams a ${side}x$side map under ulimit -v $lim KB" ||
    notok "t_filter blur under ulimit -v $lim" "$got vs $want"
t_noise -s $side -f 8 >"$T/bigy.exr"
want=$(TEXTURA_BAND_ROWS=whole t_palette marble <"$T/bigy.exr" | md5sum)
got=$(cat "$T/bigy.exr" | (ulimit -v $lim; t_palette marble) | md5sum)
[ "$got" = "$want" ] && ok "t_palette's auto range streams a ${side}x$side map under ulimit -v $lim KB" ||
    notok "t_palette auto range under ulimit -v $lim" "$got vs $want"
rm -f "$T/bigy.exr"
rm -f "$T/big.exr"

# A slow producer: half the stream, then nothing more until t_filter has written its first
# band (the producer polls its output, 20 s at most); bands of 64 rows, as on a map 64
# times as wide
t_noise -s 256x2048 >"$T/tall.exr"
size=$(stat -c %s "$T/tall.exr")
{
    head -c $((size / 2)) "$T/tall.exr"
    for _ in $(seq 200); do [ -s "$T/early.exr" ] && break; sleep 0.1; done
    [ -s "$T/early.exr" ] && date +%s.%N >"$T/first" # the first band came before the rest
    tail -c +$((size / 2 + 1)) "$T/tall.exr"
} | TEXTURA_BAND_ROWS=64 t_filter blur | cat >"$T/early.exr"
[ -s "$T/first" ] && ok "t_filter writes its first band before its input has ended" ||
    notok "t_filter waited for the whole input"
same "and the stream it wrote is whole" "$T/early.exr" <(t_filter blur <"$T/tall.exr")

# A stream cut short mid-pipeline: one line naming standard input, exit 1, nothing left
head -c $((size / 2)) "$T/tall.exr" >"$T/cut.exr"
check_fails "a truncated stream: exit 1, one line" 1 bash -c "cat '$T/cut.exr' | t_filter blur -o '$T/out.exr'"
grep -q "standard input" "$T/.err" && ok "the message names standard input" ||
    notok "truncated stream's message" "$(cat "$T/.err")"
[ ! -e "$T/out.exr" ] && ok "no output file after a truncated stream" || notok "output left behind"
# t_palette's automatic range spools its input: cut short there, or with no room to spool
check_fails "t_palette's spool of a truncated stream: exit 1, one line" 1 \
    bash -c "cat '$T/cut.exr' | t_palette marble -o '$T/pal.exr'"
grep -q "standard input" "$T/.err" && [ ! -e "$T/pal.exr" ] &&
    ok "the spool's message names standard input, and no output file is left" ||
    notok "t_palette's truncated spool" "$(cat "$T/.err")"
check_fails "t_palette with no TMPDIR to spool in: exit 1, one line" 1 \
    bash -c "TMPDIR='$T/none' t_palette marble -o '$T/pal.exr' <'$T/tall.exr'"
[ ! -e "$T/pal.exr" ] && ok "no output file when the spool cannot be made" ||
    notok "output left behind when the spool cannot be made"

