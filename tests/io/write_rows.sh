#!/usr/bin/env bash
# write_rows.sh - maps written a band of rows at a time (io/file.h tex_map_write_rows) to
# every format whose writer takes rows: PNG (libpng's rows), TIFF (scanlines), PNM, PAM,
# PBM and PFM, JPEG (libjpeg-turbo's scanlines), EXR scanline and tiled.  The bytes are
# those of the whole map's writer for any band height, and t_convert holds a band, not the
# map.
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1

# Odd sizes, no multiple of a band: one channel, RGB, and two channels (adapted by the
# writer: PNG takes them as RGB)
t_noise -s 301x203 -S 3 >y.exr
t_noise -s 301x203 -S 4 | t_palette marble >rgb.exr
t_filter gradient y.exr >ya.exr
# (ext depth): the formats and depths that take rows, to a file
cases="png: png:16 tif: tif:16 tif:32 pgm: pgm:16 ppm: pam: pam:16 pbm: pfm: jpg: exr: exr:tiles"
# (the same output name in w/ and s/: an EXR's history holds the command line)
mkdir w s
bad="" n=0
for src in y rgb ya; do
    for c in $cases; do
        # two channels: the writers that adapt them
        [ "$src" = ya ] && case $c in png: | tif: | pam: | jpg: | pfm:) ;; *) continue ;; esac
        ext=${c%%:*} d=${c#*:} opt=""
        case $d in tiles) opt="--exr-tiles" ;; ?*) opt="--depth $d" ;; esac
        # read whole and written whole (TEXTURA_BAND_ROWS=whole): today's bytes
        (cd w && TEXTURA_BAND_ROWS=whole t_convert $opt -o o.$ext <../$src.exr 2>/dev/null) || continue
        n=$((n + 1))
        rowset="7"
        [ "$src" = rgb ] && rowset="1 64 default"
        for rows in $rowset; do
            [ "$rows" = default ] && rows=""
            (cd s && cat ../$src.exr | TEXTURA_BAND_ROWS=$rows t_convert $opt -o o.$ext 2>../err) &&
                cmp -s w/o.$ext s/o.$ext || bad+=" [$src $c ${rows:-default}: $(head -c 80 err)]"
        done
    done
done
[ "$n" -ge 30 ] && [ -z "$bad" ] && ok "t_convert streams to $n kinds of file with the whole map's bytes" ||
    notok "t_convert streamed to files ($n kinds)" "$bad"

# standard output: the formats that need no seeking stream there too
bad=""
for f in png pgm ppm pam pbm jpg exr; do
    for src in y rgb; do
        want=$(TEXTURA_BAND_ROWS=whole t_convert --format $f <$src.exr 2>&1 | md5sum)
        for rows in "" 7; do
            got=$(cat $src.exr | TEXTURA_BAND_ROWS=$rows t_convert --format $f 2>&1 | md5sum)
            [ "$got" = "$want" ] || bad+=" $f/$src/${rows:-default}"
        done
    done
done
[ -z "$bad" ] && ok "t_convert --format streams to standard output with the whole map's bytes" ||
    notok "t_convert --format streamed" "$bad"

# every per-pixel and neighbourhood tool writes those formats in bands too
bad=""
for cmd in "t_filter blur --sigma 1.5" "t_remap --gamma 2" "t_palette marble --range 0,1" "t_palette marble"; do
    for ext in png tif ppm; do
        [ "$ext" = ppm ] && [ "${cmd%% *}" = t_filter ] && src=rgb || src=y
        (cd w && TEXTURA_BAND_ROWS=whole $cmd -o o.$ext <../$src.exr) && (cd s && cat ../$src.exr | TEXTURA_BAND_ROWS=7 $cmd -o o.$ext 2>../err) &&
            cmp -s w/o.$ext s/o.$ext || bad+=" [$cmd $ext: $(head -c 80 err)]"
    done
done
[ -z "$bad" ] && ok "t_filter, t_remap and t_palette write PNG, TIFF and PPM in bands" ||
    notok "tools writing other formats in bands" "$bad"

# Formats written whole still are: a mip-mapped EXR, BMP (OpenImageIO), TIFF to a pipe
for o in "--mipmap -o w.exr" "-o w.bmp" "--format tif"; do
    want=$(TEXTURA_BAND_ROWS=whole t_convert $o <y.exr 2>/dev/null | md5sum; md5sum <"${o##* }" 2>/dev/null)
    got=$(cat y.exr | t_convert $o 2>/dev/null | md5sum; md5sum <"${o##* }" 2>/dev/null)
    [ "$got" = "$want" ] && ok "t_convert $o: written whole, the same bytes" || notok "t_convert $o"
done

# A failing writer leaves nothing: a stream cut short, written to PNG
t_noise -s 256x512 | t_convert --compression none -o tall.exr
head -c 300000 tall.exr >cut.exr
truncated "a truncated stream to PNG" out.png t_convert

# Bounded memory: a 4096x4096 RGB map (192 MiB as float) to PNG, TIFF and PPM under a limit
# far below it (the whole-map writer holds the map and its 8-bit copy)
lim=$(stream_vlimit 180000) side=$(stream_side 4096)
t_noise -s $side -f 8 | t_palette --range 0,1 marble >big.exr
for ext in png; do
    t_convert -o w.$ext <big.exr
    cat big.exr | (ulimit -v $lim; t_convert -o s.$ext) 2>err
    cmp -s w.$ext s.$ext && ok "t_convert streams a ${side}x$side map to .$ext under ulimit -v $lim KB" ||
        notok "t_convert to .$ext under ulimit -v $lim" "$(head -c 200 err)"
    rm -f w.$ext s.$ext
done

# A generator writes every format that takes rows as it samples them: the bytes of its EXR
# converted, in bounded memory (every primitive of the registry, the formats that take rows)
bad=""
for name in $(t_info --primitives | awk '{ print $1 }'); do
    t_$name -s 61x37 -o g.exr 2>/dev/null || continue
    for ext in png jpg ppm tif pfm; do
        t_$name -s 61x37 -o g.$ext && t_convert -o c.$ext g.exr && cmp -s g.$ext c.$ext ||
            bad="$bad $name.$ext"
    done
done
[ -z "$bad" ] && ok "every generator's PNG, JPEG, PPM, TIFF and PFM: the bytes of its EXR converted" ||
    notok "generators' formats" "$bad"
lim=$(stream_vlimit 60000)
for ext in png tif ppm; do
    (ulimit -v $lim; t_noise -s $side -f 8 -o s.$ext) 2>err && t_noise -s $side -f 8 | t_convert -o w.$ext &&
        cmp -s w.$ext s.$ext && ok "t_noise writes a ${side}x$side .$ext in bands under ulimit -v $lim KB" ||
        notok "t_noise to .$ext under ulimit -v $lim" "$(head -c 200 err)"
    rm -f w.$ext s.$ext
done

# One rule for the EXR stream: standard output is never compressed, a regular file or a pipe,
# whether the tool streams (t_noise, t_filter) or writes the whole map (t_fft); -o compresses
for tool in "t_noise -s 300x200 -f 8" "t_filter blur y.exr" "t_fft y.exr"; do
    $tool >reg.exr && $tool | cat >piped.exr && $tool -o named.exr
    cmp -s reg.exr piped.exr && [ "$(wc -c <named.exr)" -lt "$(wc -c <reg.exr)" ] &&
        ok "${tool%% *}: an EXR to standard output has the same bytes to a regular file as to a pipe, -o's compressed" ||
        notok "${tool%% *}'s standard output" "$(wc -c reg.exr piped.exr named.exr | head -3 | tr '\n' ' ')"
done

# PNG's samples (quantised in bands, io/file.c) are PGM's (netpbm.c, lrintf) at 8 and 16 bits:
# the halves (0.5 is 127.5 and 32767.5, rounded to even), NaN, infinities, -0 and out of range
python3 - <<'PY'
import random, struct
random.seed(7)
v = [float("nan"), float("inf"), float("-inf"), -0.0, 0.5, 1.0, 2**-9, 1.5 / 255, 2.5 / 255,
     0.5 / 65535, 1.5 / 65535]
v += [random.uniform(-0.1, 1.1) for _ in range(4099 - len(v))]
open("q.pfm", "wb").write(b"Pf\n4099 1\n-1.0\n" + struct.pack("<4099f", *v))
PY
for d in 8 16; do
    t_convert --nonfinite keep q.pfm --depth $d -o q.png && t_convert --nonfinite keep q.pfm --depth $d -o q.pgm &&
        t_convert q.png -o a.pfm && t_convert q.pgm -o b.pfm && cmp -s a.pfm b.pfm &&
        ok "a $d-bit PNG's samples are a PGM's: lrintf of the clamped values, NaN 0" ||
        notok "a $d-bit PNG against a PGM" "$(cmp a.pfm b.pfm 2>&1 | head -c 200)"
done
