#!/bin/sh
# gallery.sh - a page and a contact sheet of what Textura makes: every primitive at its
# defaults and at characteristic settings, every palette as a swatch, every filter and
# remap on one map, every composition operator.  The lists come from the tools
# themselves (t_info --primitives, the palette folder, t_filter's and t_op's operation
# tables), so a new primitive, palette or operation appears by itself; each picture is
# labelled with the command that made it, ready to copy.
#   patterns/gallery.sh [-o DIR] [-s N|WxH]       (default: gallery/, pictures N = 128 wide)
# writes DIR/index.html, DIR/gallery.png (ImageMagick's montage) and DIR/*.png.
recipe=gallery # -o: the folder
size=128
fixed_seeds=1
. "$(dirname "$0")/recipe.sh"
dir=$out
mkdir -p "$dir"
cd "$dir"
: >list
n=0
# shot CMD: run a pipeline that writes PNG to standard output into the next picture
shot() {
    n=$((n + 1))
    f=$(printf 'g%03d.png' "$n")
    if sh -c "$1" >"$f" 2>err; then
        printf '%s\t%s\t%s\n' "$f" "$section" "$1" >>list
    else
        echo "gallery: failed: $1: $(cat err)" >&2
        rm -f "$f"
    fi
}
s="-s $size"
section=primitives
t_info --primitives >prims
while read -r name summary; do
    case $name in d_noise) shot "t_d_noise --normal $s --format png" ;;
    *) shot "t_$name $s --format png" ;; esac
    # characteristic settings of the primitives that have them; others show their defaults
    case $name in
    noise) shot "t_noise $s -f 24 --format png" ;;
    turbulence) shot "t_turbulence $s -f 2 -n 8 | t_palette fire --format png" ;;
    fractal)
        shot "t_fractal $s -m ridged --format png"
        shot "t_fractal $s -m midpoint --hurst 10,0,0,0,0,0,-10,10 --format png"
        shot "t_fractal $s -m julia --format png" ;;
    bubble)
        shot "t_bubble $s --value f2-f1 -c 40 --format png"
        shot "t_bubble $s --value cell -c 200 | t_palette viridis --format png" ;;
    brick) shot "t_brick $s --cells --palette brick --format png" ;;
    flower) shot "t_flower $s --petals 7 --format png" ;;
    star) shot "t_star $s --sides 7 --format png" ;;
    stripe) shot "t_stripe $s --nu 4 --format png" ;;
    wood)
        shot "t_wood $s | t_palette wood --format png"
        shot "t_wood $s --tilt 84 --axis-offset 0.4 --grain 0.3 | t_palette wood --format png" ;;
    spectral) shot "t_spectral $s --anisotropy 30,8 --format png" ;;
    holes) shot "t_holes $s --grid-cells 5 --format png" ;;
    esac
done <prims
section=palettes
awk -v w="$size" 'BEGIN { print "P2", w, 24, 255; for (y = 0; y < 24; y++) { l = "";
    for (x = 0; x < w; x++) l = l " " int(255 * x / (w - 1)); print l } }' >ramp.pgm
# the palettes of the source tree (patterns/../palettes) or the install (share/textura/palettes)
for p in $(for d in "$here/../palettes" "$here/palettes"; do
    [ -d "$d" ] && ls "$d"; done | sed -n 's/\.pal$//p' | sort -u); do
    shot "t_palette $p ramp.pgm --format png"
done
section=filters
t_turbulence $s -n 6 -S 2 -o base.exr
for op in $(t_filter --help | sed -n '/one of:/,/^$/p' | awk 'NR > 1 && NF { print $1 }'); do
    shot "t_filter $op base.exr --format png"
done
for r in "--bias 0.2" "--perlin-gain 0.8" "--gamma 2" "--levels 0.2,0.6,0,1" "--quantise 4" "--invert"; do
    shot "t_remap $r base.exr --format png"
done
section=operators
t_checker $s --ids | t_op mul - 0.4 -o a.exr
t_circle $s -o b.exr
t_info b.exr >/dev/null
# t_op's table of operators, as its message for an unknown one lists it
for op in $(t_op '?' a.exr b.exr 2>&1 | sed -n 's/.*(valid: \(.*\))$/\1/p' | tr '|' ' '); do
    case $op in abs | invert) shot "t_op $op a.exr --format png" ;;
    mix) shot "t_op mix a.exr b.exr 0.5 --format png" ;;
    *) shot "t_op $op a.exr b.exr --format png" ;; esac
done
section=synthesis
shot "t_bubble -s 48 -c 20 --tile | t_palette granite | t_synth - $s --tile --format png"
shot "t_brick -s 48 --nu 2 --nv 2 | t_synth - $s --format png"
# the page and the sheet
{
    echo '<!DOCTYPE html><html><head><meta charset="utf-8"><title>Textura gallery</title>'
    echo '<style>body{font-family:sans-serif;background:#222;color:#ddd}figure{display:inline-block;'
    echo 'margin:6px;width:'"$size"'px;vertical-align:top}figcaption{font:10px monospace;'
    echo 'word-break:break-all}img{display:block}</style></head><body><h1>Textura gallery</h1>'
    cut -f2 list | uniq | while read -r sec; do
        echo "<h2>$sec</h2>"
        awk -F'\t' -v sec="$sec" '$2 == sec { gsub(/&/, "\\&amp;", $3); gsub(/</, "\\&lt;", $3);
            gsub(/>/, "\\&gt;", $3); printf "<figure><img src=\"%s\" alt=\"\"><figcaption>%s</figcaption></figure>\n", $1, $3 }' list
    done
    echo '</body></html>'
} >index.html
if command -v montage >/dev/null; then
    set --
    while IFS="$(printf '\t')" read -r f sec cmd; do set -- "$@" -label "$cmd" "$f"; done <list
    montage "$@" -tile 8x -geometry "${size}x${size}+6+6" -pointsize 8 -background '#222222' \
        -fill '#dddddd' gallery.png
fi
rm -f err prims ramp.pgm a.exr b.exr base.exr
echo "wrote $dir/index.html and $dir/gallery.png ($(wc -l <list) pictures)"
