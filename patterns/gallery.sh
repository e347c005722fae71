#!/bin/sh
# gallery.sh - a page and a contact sheet of what Textura makes: every tool, with the maps
# it reads shown beside what it writes; every primitive at its defaults and at
# characteristic settings, every fractal mode, the composed primitives; every palette,
# filter, remap and operator on inputs chosen so that each effect shows at thumbnail size;
# transforms, cascades, spectra, synthesis, scenes and the thesis's figures.  The lists
# come from the tools themselves (t_info --primitives, the palette folder, t_filter's,
# t_op's and t_fractal's tables), so a new primitive, palette or operation appears by
# itself; each picture is labelled with the command that made it, ready to copy in the
# gallery's folder, where its inputs are kept.
#   patterns/gallery.sh [-o DIR] [-s N|WxH]       (default: gallery/, thumbnails N = 128 wide)
# writes DIR/index.html (a click enlarges a picture, drawn at 2N), DIR/gallery.png
# (ImageMagick's montage), the pictures and the inputs.
recipe=gallery # -o: the folder
size=128
fixed_seeds=1
. "$(dirname "$0")/recipe.sh"
dir=$out
mkdir -p "$dir"
cd "$dir"
: >list
n=0
big=$((2 * W)) # drawn at twice the thumbnail: the page shows it at W, a click at full size
s="-s $big"
tab=$(printf '\t')
one_line() { printf '%s' "$1" | tr '\n' ' ' | tr -s ' '; }
# shot CMD [INPUTS]: a pipeline that writes PNG on standard output, as the next picture;
# INPUTS are the names of the maps it reads (NAME.exr, shown as NAME.png beside it)
shot() {
    n=$((n + 1))
    f=$(printf 'g%03d.png' "$n")
    if sh -c "$1" >"$f" 2>err; then
        printf '%s\t%s\t%s\t%s\n' "$f" "$section" "$(one_line "$1")" "${2:-}" >>list
    else
        echo "gallery: failed: $1: $(cat err)" >&2
        rm -f "$f"
    fi
}
# input NAME CMD: an input map the later pictures read, kept as NAME.exr and shown as
# NAME.png (region ids spread over 0..1 to be seen)
input() {
    if sh -c "$2 -o $1.exr" 2>err; then
        case $1 in ids) t_remap --levels 1,2,0,1 "$1.exr" -o "$1.png" ;;
        *) t_convert "$1.exr" -o "$1.png" ;; esac
        printf '%s\t%s\t%s\t%s\n' "$1.png" "$section" "$(one_line "$2") -o $1.exr" "" >>list
    else
        echo "gallery: failed: $2: $(cat err)" >&2
    fi
}

section="inputs of the pictures below"
input fbm "t_fractal $s -f 3 -S 2"
input base "t_checker $s --nu 4 --nv 4 --ids | t_remap --levels 1,2,0.25,0.75 |
    t_op mix - fbm.exr 0.35 | t_filter noise --stddev 0.1 -S 4"
input grey "t_checker $s --nu 3 --nv 3 --ids | t_remap --levels 1,2,0.2,0.8"
input ramp "t_expr -s ${big}x$((big / 6)) u"
t_palette --from '#ffffff00' --to '#e06a20ff' --stops 2 -o disc.pal
t_palette --from '#ffffff00' --to '#2050c0d0' --stops 2 -o bars.pal
input disc "t_circle $s --ids | t_op sub - 1 | t_palette disc.pal"
input bars "t_stripe $s --nu 3 --ids | t_op sub - 1 | t_palette bars.pal"
input ids "t_circle $s --ids"
input sample "t_bubble -s 64 -c 20 -S 5 --tile | t_palette granite"
input magnitude "t_ring $s -r 0.12 --ring-width 0.02 --ids | t_remap --levels 1,3,0,1"

section=primitives
t_info --primitives >prims
while read -r name summary; do
    case $name in d_noise) shot "t_d_noise --normal $s --format png" ;;
    fractal) ;; # below, every mode
    *) shot "t_$name $s --format png" ;; esac
    # characteristic settings of the primitives that have them; others show their defaults
    case $name in
    noise) shot "t_noise $s -f 24 --format png" ;;
    turbulence) shot "t_turbulence $s -f 2 -n 8 | t_palette fire --format png" ;;
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
section="fractal modes"
for m in $(t_fractal --help | sed -n 's/.*--mode NAME .*\[\([a-z|]*\)\].*/\1/p' | tr '|' ' '); do
    case $m in
    midpoint) shot "t_fractal $s -m midpoint --hurst 10,0,0,0,0,0,-10,10 --format png" ;;
    mandelbrot | julia) shot "t_fractal $s -m $m | t_palette fire --format png" ;;
    *) shot "t_fractal $s -m $m --format png" ;;
    esac
done
section="composed primitives"
cp "$here/primitives.tp" .
for p in $(sed -n 's/^primitive \([a-z_]*\)(.*/\1/p' primitives.tp); do
    shot "t_expr --defs primitives.tp $p $s --format png"
done
shot "t_expr $s 'fractal() + 0.3 * circle()' --format png"
section=palettes
for p in $(for d in "$here/../palettes" "$here/palettes"; do
    [ -d "$d" ] && ls "$d"; done | sed -n 's/\.pal$//p' | sort -u); do
    shot "t_palette $p ramp.exr --format png" ramp
done
section=filters
# settings that show each effect at thumbnail size; an operation not named here shows
# its defaults
for op in $(t_filter --help | sed -n '/one of:/,/^$/p' | awk 'NR > 1 && NF { print $1 }'); do
    case $op in
    blur) a="--sigma 3" ;; box) a="--radius 4" ;; median) a="--radius 2" ;;
    sharpen) a="--sigma 2 --strength 1.5" ;; sobel | emboss) a="--strength 3" ;;
    edges) a="--strength 2" ;; noise) a="--stddev 0.15" ;; normal) a="--strength 4" ;;
    *) a="" ;;
    esac
    shot "t_filter $op ${a:+$a }base.exr --format png" base
done
section=remaps
for r in "--bias 0.75" "--perlin-gain 0.85" "--gamma 2" "--levels 0.3,0.7,0,1" "--quantise 4" \
    "--invert"; do
    shot "t_remap $r fbm.exr --format png" fbm
done
section=operators
# t_op's table of operators, as its message for an unknown one lists it
for op in $(t_op '?' 2>&1 | sed -n 's/.*(valid: \(.*\))$/\1/p' | tr '|' ' '); do
    case $op in
    abs) shot "t_op sub fbm.exr grey.exr | t_op abs - --format png" "fbm grey" ;;
    invert | threshold) shot "t_op $op fbm.exr --format png" fbm ;;
    mix) shot "t_op mix fbm.exr grey.exr 0.5 --format png" "fbm grey" ;;
    over | under) shot "t_op $op disc.exr bars.exr --format png" "disc bars" ;;
    *) shot "t_op $op fbm.exr grey.exr --format png" "fbm grey" ;;
    esac
done
section="transforms and warps"
shot "t_xform --rotate 30 grey.exr --format png" grey
shot "t_xform --scale 2 --shift 40,20 --wrap sample.exr --format png" sample
shot "t_xform --expand 192x192 --rotate 45 --around 96,96 disc.exr --format png" disc
shot "t_warp grey.exr fbm.exr --displacement 0.15 --neutral 0.5 --format png" "grey fbm"
shot "t_tile --nu 3 --nv 3 sample.exr --format png" sample
shot "t_tile --nu 3 --nv 3 --mirror sample.exr --format png" sample
section="cascades and composition"
shot "t_cascade ids.exr 1=fbm.exr 2=sample.exr --resize scale --format png" "ids fbm sample"
cp "$here/tessellation.tc" .
shot "t_compose tessellation.tc --format png"
section="spectra and synthesis"
shot "t_fft base.exr --as logmag --format png" base
shot "t_ifft magnitude.exr --format png" magnitude
shot "t_sparse sample.exr $s --format png" sample
shot "t_synth sample.exr $s --tile --format png" sample
section=scenes
cp "$here/still_life.scene" "$here/resolution.scene" "$here/fireball.scene" "$here/smoke_csg.scene" .
shot "t_noise -s 256 -f 12 -S 7 | t_apply still_life.scene -s ${big}x$((3 * big / 4)) -q --format png"
shot "t_apply resolution.scene -s ${big}x$((9 * big / 16)) -q --format png"
shot "t_apply fireball.scene -s ${big}x$((3 * big / 4)) -q --format png"
shot "t_apply smoke_csg.scene -s ${big}x$((3 * big / 4)) -q --format png"
# the thesis's figures as make figures left them (the source tree's doc/figures)
figs=$here/../doc/figures
if [ -f "$figs/figures.md" ]; then
    section="the thesis's figures (make figures)"
    awk '/^## / { name = $2; next } name && NF && !/^!\[/ && !/^```/ && !cap[name]++ {
        print name "\t" $0 }' "$figs/figures.md" | while IFS="$tab" read -r name cap; do
        [ -f "$figs/fig_$name.png" ] || continue
        cp "$figs/fig_$name.png" "fig_$name.png"
        printf '%s\t%s\t%s\t%s\n' "fig_$name.png" "$section" "$cap" "" >>list
    done
fi

# the page: each picture with its inputs beside it and its command under it
# a caption's words each in a span that breaks only when wider than a line (a browser
# would break "--nv" after its hyphens)
html() {
    sed 's/&/\&amp;/g; s/</\&lt;/g; s/>/\&gt;/g' |
        awk '{ for (i = 1; i <= NF; i++) printf "%s<span>%s</span>", (i > 1 ? " " : ""), $i }'
}
{
    echo '<!DOCTYPE html><html><head><meta charset="utf-8"><title>Textura gallery</title>'
    echo '<style>body{font-family:sans-serif;background:#222;color:#ddd}'
    echo 'figure{display:inline-block;margin:6px;width:'"$W"'px;vertical-align:top}'
    echo 'figcaption{font:10px monospace;word-break:normal}'
    echo 'figcaption span{display:inline-block;max-width:100%;overflow-wrap:anywhere}'
    echo 'img.pic{display:block;width:'"$W"'px}.in{display:flex;gap:2px;font:9px sans-serif}'
    echo '.in img{display:block;width:'"$((W / 3 - 2))"'px}</style></head><body><h1>Textura gallery</h1>'
    echo '<p>Each command runs in this folder, which keeps the maps it reads; the small'
    echo 'pictures above a result are its inputs. Click a picture to see it at full size.</p>'
    cut -f2 list | uniq | while read -r sec; do
        echo "<h2>$sec</h2>"
        while IFS="$tab" read -r f fsec cmd ins; do
            [ "$fsec" = "$sec" ] || continue
            printf '<figure>'
            if [ -n "$ins" ]; then
                printf '<div class="in">'
                for i in $ins; do
                    printf '<a href="%s.png"><img src="%s.png" alt="%s" title="input %s.exr"></a>' \
                        "$i" "$i" "$i" "$i"
                done
                printf '</div>'
            fi
            printf '<a href="%s"><img class="pic" src="%s" alt="" data-inputs="%s"></a>' "$f" "$f" "$ins"
            printf '<figcaption>%s</figcaption></figure>\n' "$(printf '%s' "$cmd" | html)"
        done <list
    done
    echo '</body></html>'
} >index.html
# the contact sheet: captions wrapped at spaces to the thumbnail's width, at most six
# lines (montage makes every tile as tall as the tallest label), in DejaVu Sans (make
# deps' fonts-dejavu-core: montage's default font is looked up again for every label)
if command -v montage >/dev/null; then
    cols=$((W / 5))
    set --
    while IFS="$tab" read -r f sec cmd ins; do
        label=$(printf '%s' "$cmd" | fold -s -w "$cols" | awk 'NR <= 6 { print } NR == 7 { print "..." }')
        set -- "$@" -label "$label" "$f"
    done <list
    montage "$@" -tile 8x -geometry "${W}x${W}+6+6" -font DejaVu-Sans -pointsize 8 \
        -background '#222222' -fill '#dddddd' gallery.png
fi
rm -f err prims
echo "wrote $dir/index.html and $dir/gallery.png ($(wc -l <list) pictures)"
