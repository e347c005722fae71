#!/bin/sh
# loop.sh - a looping animation (thesis ch. 6, dynamic textures in time): marble veins of
# turbulence moving through 4D noise on a circle, so that the last frame leads back into
# the first as smoothly as any frame into the next.  With ffmpeg installed it also encodes
# a looping GIF and an MP4; without it, the frames alone.
#   patterns/loop.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_0000.png ... (frames=N in the
#                                            environment, default 24), PREFIX.gif, PREFIX.mp4
recipe=loop
size=${size:-256}
. "$(dirname "$0")/recipe.sh"
frames=${frames:-24}
case $frames in '' | *[!0-9]* | 0) echo "$0: frames must be a whole number >= 1 (got '$frames')" >&2; exit 2 ;; esac
k=0
while [ "$k" -lt "$frames" ]; do
    name=$(printf '%s_%04d.png' "$out" "$k")
    t_turbulence -s "$size" -f 3 -n 6 -S $((5 + S)) --frames "$frames" --frame "$k" --loop-radius 0.3 |
        t_palette marble -o "$name"
    k=$((k + 1))
done
echo "wrote $frames frames ${out}_0000.png .. $(printf '%s_%04d.png' "$out" $((frames - 1)))"
if command -v ffmpeg >/dev/null 2>&1; then
    # One palette for the whole GIF; -loop 0 repeats it for ever.
    ffmpeg -loglevel error -y -framerate 12 -i "${out}_%04d.png" \
        -vf "split[a][b];[a]palettegen[p];[b][p]paletteuse" -loop 0 "$out.gif" &&
        echo "wrote $out.gif"
    ffmpeg -loglevel error -y -framerate 24 -i "${out}_%04d.png" -pix_fmt yuv420p \
        -vf "pad=ceil(iw/2)*2:ceil(ih/2)*2" "$out.mp4" && echo "wrote $out.mp4"
else
    echo "ffmpeg not installed: frames only (apt-get install ffmpeg for the GIF and video)"
fi
