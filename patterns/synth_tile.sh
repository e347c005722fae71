#!/bin/sh
# synth_tile.sh - a tileable texture from a photo-like sample: bubbles coloured by a
# palette stand in for a photo of a material; t_synth grows a seamless map from it.
#
#   patterns/synth_tile.sh [OUT.png] [SIZE] [SEED]    (default synth_tile.png 1024 7)
#
# Any photo works in place of the sample: t_synth PHOTO.png -s 1024 --tile -o OUT.png.
# The tools must be on PATH (build/bin).
set -eu
out=${1:-synth_tile.png}
size=${2:-1024}
seed=${3:-7}
t_bubble -s 128 -c 40 -S "$seed" --size-spread 0.4 | t_palette marble |
    t_synth -s "$size" --tile -S "$seed" -o "$out"
echo "wrote $out (${size}x$size, tiles seamlessly)"
