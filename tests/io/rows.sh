#!/usr/bin/env bash
# rows.sh - the row reader (io/stream.h tex_rows_open, io/file.h tex_map_open_rows) behind
# every tool that streams its input: a tiled or mip-mapped EXR on a pipe is read whole, as
# the whole-map reader reads it (it was refused, "standard input: tiled: read whole"), and
# the input limit (TEXTURA_MAX_INPUT, io/limit.h) holds as for the whole-map readers, with
# their words; t_info gathers a stream's figures in bounded memory.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# The tools that read their input through the row reader (tex_map_open_rows,
# tex_cli_stream, tex_cli_stream_window), each with a command that streams
tools=("t_filter blur --sigma 1.5" "t_filter median" "t_palette marble --range 0,1"
       "t_palette marble" "t_remap --gamma 2" "t_convert" "t_info" "t_info --json")

# Odd sizes: no band or tile divides them
t_noise -s 301x203 -S 5 | t_convert --exr-tiles -o tiled.exr
t_noise -s 301x203 -S 6 | t_convert --mipmap -o mip.exr
for f in tiled mip; do
    bad="" badpath=""
    for cmd in "${tools[@]}"; do
        # the whole map's bytes (TEXTURA_BAND_ROWS=whole): those a pipe must give
        want=$(TEXTURA_BAND_ROWS=whole $cmd <$f.exr 2>&1 | md5sum)
        got=$(cat $f.exr | $cmd 2>err | md5sum)
        [ "$got" = "$want" ] && [ ! -s err ] || bad+=" [$cmd: $(head -c 80 err)]"
        for rows in 7; do # a tiled map is read whole: the bands are the next stage's
            got=$(cat $f.exr | TEXTURA_BAND_ROWS=$rows $cmd 2>/dev/null | md5sum)
            [ "$got" = "$want" ] || bad+=" [$cmd/$rows rows]"
        done
        # from a path: the same pixels (t_info: the same figures); the history names the path
        case $cmd in
        t_info*) diff <($cmd $f.exr | sed 1d | grep -v "^  t_\|history") <($cmd <$f.exr | sed 1d | grep -v "^  t_\|history") >/dev/null ||
                     badpath+=" [$cmd]" ;;
        *) $cmd $f.exr -o p.exr 2>err && $cmd <$f.exr -o w.exr &&
               d=$(maxdiff p.exr w.exr) && approx "$d" 0 0 || badpath+=" [$cmd: $(head -c 80 err)]" ;;
        esac
    done
    [ -z "$bad" ] && ok "a $f EXR on a pipe: every streaming tool gives the whole map's bytes" ||
        notok "a $f EXR on a pipe" "$bad"
    [ -z "$badpath" ] && ok "a $f EXR from a path: every streaming tool gives the whole map's pixels" ||
        notok "a $f EXR from a path" "$badpath"
done
# a tiled stream through a pipeline of streaming stages
t_noise -s 300 | t_convert --exr-tiles -o t300.exr
want=$(t_filter blur <t300.exr | t_palette marble --range 0,1 | t_remap --gamma 2 | t_info)
got=$(cat t300.exr | t_filter blur | t_palette marble --range 0,1 | t_remap --gamma 2 | t_info)
[ "$got" = "$want" ] && ok "t_convert --exr-tiles | t_filter | t_palette | t_remap | t_info" ||
    notok "a tiled stream through a pipeline" "$got"
# a tiled stream cut short: one line naming standard input
head -c 40000 t300.exr >cut.exr
truncated "a truncated tiled stream" out.exr t_filter blur

# The input limit: a 64x64 map declares 16384 bytes as float, its stream is about 17.8 KB.
# Every streaming tool refuses what the whole-map reader refuses, with its words.
t_noise -s 64 | cat >n.exr # the stream as a pipe carries it: uncompressed
t_noise -s 64 | t_convert --compression none -o u.exr
t_noise -s 64 | t_convert --compression zip -o z.exr # smaller than the map: judged by its size
[ "$(stat -c %s n.exr)" -gt 17408 ] && [ "$(stat -c %s u.exr)" -gt 17408 ] ||
    notok "the stream and u.exr are larger than 17K" "$(stat -c %s n.exr u.exr)"
declared="standard input: 64x64 with 1 channel is 16384 bytes as float, over the input limit of 15360 (TEXTURA_MAX_INPUT)"
for cmd in "${tools[@]}"; do
    TEXTURA_MAX_INPUT=15K check_fails "$cmd: a stream declaring more than the limit" 1 bash -c "cat n.exr | $cmd"
    grep -qF "$declared" "$T/.err" || notok "$cmd: the declared size's words" "$(cat "$T/.err")"
    TEXTURA_MAX_INPUT=17K check_fails "$cmd: a stream whose bytes pass the limit" 1 bash -c "cat n.exr | $cmd"
    grep -qF "standard input: over the input limit of 17408 bytes (TEXTURA_MAX_INPUT)" "$T/.err" ||
        notok "$cmd: the counted bytes' words" "$(cat "$T/.err")"
    TEXTURA_MAX_INPUT=17K check_fails "$cmd: a file over the limit" 1 $cmd u.exr
    grep -qF "u.exr: over the input limit of 17408 bytes (TEXTURA_MAX_INPUT)" "$T/.err" ||
        notok "$cmd: a file's words" "$(cat "$T/.err")"
    TEXTURA_MAX_INPUT=20K check "$cmd: a stream under the limit passes" bash -c "cat n.exr | $cmd"
    TEXTURA_MAX_INPUT=17K check "$cmd: a compressed file under the limit passes" $cmd z.exr
done
# the whole-map reader of a pipe says the same (t_op reads its maps whole)
TEXTURA_MAX_INPUT=17K check_fails "t_op, a stream whose bytes pass the limit" 1 bash -c "cat n.exr | t_op add - 0 -o out2.exr"
grep -qF "standard input: over the input limit of 17408 bytes (TEXTURA_MAX_INPUT)" "$T/.err" ||
    notok "t_op: the same words" "$(cat "$T/.err")"
[ ! -e out2.exr ] && ok "no output after a refusal" || notok "output left behind"

# Unset, the limit holds a read in rows to what its header declares, not to 2 GiB: such a
# read holds a band, never the map (issue 58). A 65536^2 stream (16 GiB as float) cut after
# 8 MB ends early, at its row; with the variable set, the declared size is refused as before.
for cmd in "t_filter blur --sigma 1.5 -o big.exr" "t_palette marble --range 0,1 -o big.exr" \
    "t_remap --gamma 2 -o big.exr" "t_convert -o big.exr" "t_info"; do
    check_fails "$cmd: a 65536^2 stream cut short" 1 bash -c "t_noise -s 65536 | head -c 8000000 | $cmd"
    grep -qE "standard input: truncated OpenEXR data at scanline (2[0-9]|30)$" "$T/.err" ||
        notok "$cmd: the row where it ended" "$(cat "$T/.err")"
    TEXTURA_MAX_INPUT=1G check_fails "$cmd: a 65536^2 stream over a limit set" 1 \
        bash -c "t_noise -s 65536 | head -c 8000000 | $cmd"
    grep -qF "65536x65536 with 1 channel is 17179869184 bytes as float, over the input limit" "$T/.err" ||
        notok "$cmd: the declared size's words" "$(cat "$T/.err")"
done
[ ! -e big.exr ] && ok "no output from a stream cut short" || notok "output left behind"

# t_info streams: a 4096x4096 RGB map (192 MiB) under a limit far below it
lim=$(stream_vlimit 180000) side=$(stream_side 4096)
t_noise -s $side -f 8 | t_palette --range 0,1 marble >big.exr
want=$(TEXTURA_BAND_ROWS=whole t_info <big.exr)
got=$(cat big.exr | (ulimit -v $lim; t_info))
[ "$got" = "$want" ] && ok "t_info reads a ${side}x$side stream under ulimit -v $lim KB" ||
    notok "t_info under ulimit -v $lim" "$got"
got=$( (ulimit -v $lim; t_info big.exr) | sed 1d)
[ "$got" = "$(sed 1d <<<"$want")" ] && ok "and the file, a band at a time" || notok "t_info big.exr under ulimit -v $lim" "$got"

# A FIFO named as the input, as <( ) gives it: read as a pipe (the bytes taken to sniff it
# were lost when the path was opened again: "unknown image format")
t_noise -s 301x203 -S 7 >f.exr
bad=""
for cmd in "t_filter blur" "t_remap --gamma 2" "t_palette marble" "t_convert"; do
    $cmd f.exr -o p.exr && $cmd <(cat f.exr) -o q.exr 2>err && d=$(maxdiff p.exr q.exr) &&
        approx "$d" 0 0 || bad+=" [$cmd: $(head -c 100 err)]"
done
t_info <(cat tiled.exr) | sed 1d >fi.txt && t_info tiled.exr | sed 1d | cmp -s - fi.txt || bad+=" [t_info tiled]"
[ -z "$bad" ] && ok "a FIFO named on the command line streams" || notok "a FIFO named on the command line" "$bad"
