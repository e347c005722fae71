#!/bin/sh
# synth_tile.sh - a tileable texture from a photo-like sample: bubbles coloured by a
# palette stand in for a photo of a material; t_synth grows a seamless map from it.
#   patterns/synth_tile.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_sample, PREFIX_tile
#                                                              (default size 1024)
# Any photo works in place of the sample: t_synth PHOTO.png -s 1024 --tile -o OUT.png.
recipe=synth_tile
size=${size:-1024}
. "$(dirname "$0")/recipe.sh"
t_bubble -s 128 -c 40 -S $((7 + S)) --size-spread 0.4 | t_palette marble -o "$tmp/sample.exr"
t_synth -s "$size" --tile -S $((7 + S)) -o "$tmp/tile.exr" "$tmp/sample.exr"
write "$tmp/sample.exr" sample
write "$tmp/tile.exr" tile
