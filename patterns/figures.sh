#!/bin/sh
# figures.sh - the thesis's figures and photos that are pictures, rebuilt from the real
# primitives, and the seed paper's five spheres: DIR/fig_ID.png and .exr for each, and
# DIR/figures.md, a page with each one's caption (translated) and the commands that made it.
#   patterns/figures.sh [-o DIR] [-s N|WxH]      (default doc/figures, maps N = 256 wide)
#   FIGURES="ID ..." patterns/figures.sh ...  (only those figures)
# `make figures` runs it; tests/tools/figures.sh checks each figure against a golden image.
recipe=doc/figures # -o: the folder
size=256
fixed_seeds=1
. "$(dirname "$0")/recipe.sh"
dir=$out
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
cd "$tmp"
s=$size h=$((W / 2))
page=$dir/figures.md
printf '# The thesis'"'"'s figures, rebuilt\n\nMade by `make figures` (patterns/figures.sh); each is checked against a golden image by tests/tools/figures.sh. Captions are translated from the thesis and the colour-model paper (Ferreira 1991).\n' >"$page"
# figure ID CAPTION COMMANDS: run the commands (which leave fig.exr), keep it as fig_ID, and
# put it on the page with its caption and commands; with $FIGURES set, only the figures it
# lists (make figures renders the README's Photo 4.1 at 800 x 600 so)
figure() {
    [ -z "${FIGURES:-}" ] || case " $FIGURES " in *" $1 "*) ;; *) return 0 ;; esac
    sh -eu -c "$3"
    t_convert fig.exr -o "$dir/fig_$1.exr"
    t_convert fig.exr -o "$dir/fig_$1.png"
    # the recipes by their place in the source tree, not this machine's
    printf '\n## %s\n\n%s\n\n![%s](fig_%s.png)\n\n```sh\n%s\n```\n' "$1" "$2" "$1" "$1" \
        "$(printf '%s\n' "$3" | sed "s|'$here/\([^']*\)'|patterns/\\1|g")" >>"$page"
    echo "wrote fig_$1"
}
figure 4.7 "Figure 4.7: The texture maps of the wood plank, left to right: the map for the colour, the map for the brightness (constant: a varnish shines alike everywhere), the map for the roughness (nearly parallel line segments, applied as a bump)." "
'$here/wood_plank.sh' -o wood -s $s >/dev/null
t_tile --matrix cycle --nu 3 --nv 1 -s $((3 * h))x$h wood_colour.exr wood_brightness.exr wood_roughness.exr -o fig.exr"
figure 5.1 "Figure 5.1: t_flower in different instances, for different values of the colours, the number of petals and the petal length." "
t_flower -s $h -o f1.exr
t_flower -s $h --petals 3 --petal-length 0.3 --colour1 '#f4efe2' --colour2 '#b8322a' -o f2.exr
t_flower -s $h --petals 8 --petal-length 0.48 --colour1 '#203050' --colour2 '#e0e8f0' -o f3.exr
t_flower -s $h --petals 4 --petal-length 0.4 --colour1 '#e8c060' --colour2 '#603010' -o f4.exr
t_tile --matrix cycle --nu 4 --nv 1 -s $((2 * s))x$h f1.exr f2.exr f3.exr f4.exr -o fig.exr"
figure 5.3 "Figure 5.3: Some of the geometric primitives implemented." "
for p in circle ring ellipse flower star polygon stripe checker brick four_rings cycloid hypocycloid; do
    t_\$p -s $((s / 3)) -o \$p.exr
done
t_tile --matrix cycle --nu 4 --nv 3 -s $((4 * s / 3))x$s circle.exr ring.exr ellipse.exr flower.exr \\
    star.exr polygon.exr stripe.exr checker.exr brick.exr four_rings.exr cycloid.exr hypocycloid.exr -o fig.exr"
figure 5.4 "Figure 5.4: Several maps generated from the ellipse primitive (the ellipse, blurred, its gradient magnitude, embossed, its edges enhanced, its normal map)." "
t_ellipse -s $h --palette greys -o e.exr
t_filter blur --sigma 3 e.exr -o b.exr
t_filter sobel e.exr -o g.exr
t_filter emboss --strength 2 e.exr -o m.exr
t_filter edges --strength 2 e.exr -o d.exr
t_filter normal --strength 4 b.exr -o n.exr
t_tile --matrix cycle --nu 3 --nv 2 -s $((3 * h))x$((2 * h)) e.exr b.exr g.exr m.exr d.exr n.exr -o fig.exr"
figure 5.6 "Figure 5.6: An instance of the function t_turbulence." "
t_turbulence -s $s -n 7 -S 2 -o fig.exr"
figure 5.7 "Figure 5.7: The Koch curve." "
t_fractal -m koch --koch curve -s $s -o fig.exr"
figure 5.8 "Figure 5.8: The matrix of texture models of diagonal_flower: a circle where u' = v', a flower elsewhere." "
t_circle -s $((s / 3)) -o c.exr
t_flower -s $((s / 3)) --petals 4 -o f.exr
t_tile --matrix diagonal --nu 3 --nv 3 -s $s c.exr f.exr -o fig.exr"
figure 5.9 "Figure 5.9: The texture cascade of cascade_circle_flower: where t_circle gives subregion 1 (the outside, as Figure 5.2 numbers it), the texture is t_flower." "
t_circle -s $s --ids -o ids.exr
t_flower -s $s --petals 5 -o f.exr
t_cascade ids.exr 1=f.exr --default '#204060' -o fig.exr"
figure 5.10 "Figure 5.10: The function t_turbulence composed with the primitive t_stripe (domain perturbation): marble veins." "
t_stripe -s $s -o st.exr
t_turbulence -s $s -S 2 --tile -o tu.exr
t_warp st.exr tu.exr --displacement 0.1 --edge clamp -o fig.exr"
figure 5.11 "Figure 5.11: Repetitions of a t_stripe primitive." "
t_stripe -s $((s / 3)) -a 30 -o s1.exr
t_tile --nu 3 --nv 2 -s ${s}x$((2 * s / 3)) s1.exr -o fig.exr"
figure 5.12 "Figure 5.12: The same t_stripe primitive repeated in mirror." "
t_stripe -s $((s / 3)) -a 30 -o s1.exr
t_tile --nu 3 --nv 2 --mirror -s ${s}x$((2 * s / 3)) s1.exr -o fig.exr"
figure 5.13 "Figure 5.13: Effects of varying the application function: one map of turbulence applied to the diffuse colour, the specular coefficient, the normal (bump) and the reflection." "
t_turbulence -s 256 -n 6 -S 4 -o t.exr
cat >s.scene <<S
image 800 240
ambient 0.3 0.3 0.3
background 0.2 0.25 0.3
camera { eye 0 1.6 -12 look 0 0.8 0 fov 40 }
light point { position -4 5 -6 intensity 1 }
texture t file \"t.exr\"
surface kd { Kd 0.8 0.5 0.3 apply t { mapping sphere Kd = 2 * f * p } }
surface ks { Kd 0.3 0.35 0.6 Ks 0.9 n 40 apply t { mapping sphere Ks = 2.5 * f } }
surface bump { Kd 0.7 0.7 0.7 Ks 0.4 n 30 apply t { mapping sphere repeat 2 1 bump = 0.01 } }
surface kr { Kd 0.2 0.2 0.25 Ks 0.6 n 80 Kr 0.5 apply t { mapping sphere Kr = 2 * f } }
surface floor { Kd 0.5 0.5 0.45 }
sphere { centre -3 0.9 0 radius 0.9 surface kd }
sphere { centre -1 0.9 0 radius 0.9 surface ks }
sphere { centre 1 0.9 0 radius 0.9 surface bump }
sphere { centre 3 0.9 0 radius 0.9 surface kr }
plane { surface floor }
S
t_apply s.scene -s $((2 * s))x$((3 * s / 5)) -q -o fig.exr"
figure orange_peel "Section 2.3.3: the orange peel, midpoint displacement with one Hurst exponent per level (h = 10, 0, 0, 0, 0, 0, -10, 10), as a bump." "
'$here/orange_peel.sh' -o op -s $s >/dev/null
t_convert op_render.exr -o fig.exr"
figure photo_4.1 "Photo 4.1: A synthetic scene with the wood texture, modelled as section 4.5 does: the colour from concentric ellipses with perturbed edges and dark lines between them, a uniform brightness (a varnish of high specularity), and a roughness of randomly placed, nearly parallel line segments applied as a bump; a brick wall whose bricks vary in colour at random, and a vase of marble made as a solid texture. Top left, the same scene before texturing." "
'$here/wood_plank.sh' -o wood -s $((2 * s)) >/dev/null
# the grain along the table's length (x, the planar mapping's u), one plank across it
t_xform --rotate 90 wood_colour.exr -o wood_u.exr
t_xform --rotate 90 wood_roughness.exr -o grooves_u.exr
printf 'space oklab\\n0 #6e2a1a\\n0.35 #9a3b22\\n0.7 #b5573a\\n1 #c98a5a\\nindex 1 #cfc6b8\\n' >clay.pal
t_brick -s 512 --nu 4 --nv 8 --cells --palette clay.pal -S 7 --tile -o bricks.exr
t_brick -s 512 --nu 4 --nv 8 --tile --palette greys | t_filter blur --sigma 1.5 --edge wrap -o mortar.exr
cat >s.scene <<S
samples 4
ambient 0.3 0.3 0.3
camera { eye 0.3 2.3 -4.2 look 0 1.1 1 fov 50 }
light point { position -2.5 4.5 -3 intensity 0.9 }
light distant { direction 2 2 -1 intensity 0.3 }
texture wood file \"wood_u.exr\"
texture grooves file \"grooves_u.exr\"
texture bricks file \"bricks.exr\"
texture mortar file \"mortar.exr\"
texture veins turbulence { solid frequency 2 octaves 6 seed 3 }
surface varnish { Ka 0.4 Kd 0.8 0.55 0.35 Ks 0.6 n 90 Kr 0.08
    apply wood { mapping planar scale 0.25 Kd = f }
    apply grooves { mapping planar scale 0.25 bump = -0.002 }
}
surface wall { Ka 0.5 Kd 0.75 0.45 0.35
    apply bricks { mapping natural repeat 3 1 Kd = f }
    apply mortar { mapping natural repeat 3 1 bump = 0.02 }
}
surface marble { Ka 0.35 Kd 0.9 0.88 0.85 Ks 0.6 n 80 Kr 0.06
    apply veins { mapping solid Kd = palette(marble, 0.5 + 0.5 * sin(6 * ox + 12 * f)) }
}
surface floor { Ka 0.4 Kd 0.35 0.33 0.3 }
box { min -2 0.9 -1 max 2 1 1.2 surface varnish }
box { min -1.8 0 -0.8 max -1.6 0.9 -0.6 surface varnish }
box { min 1.6 0 -0.8 max 1.8 0.9 -0.6 surface varnish }
box { min -1.8 0 0.8 max -1.6 0.9 1 surface varnish }
box { min 1.6 0 0.8 max 1.8 0.9 1 surface varnish }
box { min -4 0 2 max 4 3.5 2.3 surface wall }
union { sphere { centre 0.6 1.45 0.3 radius 0.45 } cylinder { base 0.6 1.7 0.3 top 0.6 2.2 0.3 radius 0.16 }
    surface marble }
plane { surface floor }
S
t_apply s.scene -s ${s}x$((3 * s / 4)) -q -o scene.exr
# the inset, top left: the scene before texturing, a quarter as wide, in a white frame
grep -v 'apply ' s.scene >plain.scene
t_apply plain.scene -s $((s / 4))x$((3 * s / 16)) -q |
    t_xform --expand $((s / 4 + 4))x$((3 * s / 16 + 4)) --background 1,1,1 -o inset.exr
place=\"--expand ${s}x$((3 * s / 4)) --shift $((s / 64 - 3 * s / 8 + 2)),$((s / 64 - 9 * s / 32 + 2))\"
t_xform \$place inset.exr -o over.exr
t_op mul inset.exr 0 | t_op add - 1 | t_xform \$place -o mask.exr
t_op mix scene.exr over.exr mask.exr -o fig.exr"
figure photo_6.1 "Photo 6.1: Imitation of a fabric texture from a fractal primitive: a 2/2 twill of indigo warp and paler weft threads with irregular yarns (t_weave), its dye mottled by fBm." "
'$here/fabric.sh' -o fab -s $s >/dev/null
t_convert fab_colour.exr -o fig.exr"
figure ferreira_5 "Ferreira (1991), Figure 5: the five spheres rendered with Whitted-Phong in RGB (left) and Cook-Torrance with sampled spectra (right)." "
'$here/five_spheres.sh' -o five -s ${s}x$((3 * s / 4)) >/dev/null
t_convert five_render.exr -o fig.exr"
figure brushed_steel "Anisotropic reflection, which section 5.2.4 leaves as future work (Kajiya 1985): brushed stainless steel, smooth along its grooves and rough across them. The plate (Ward's model) is brushed in swirls along the contour lines of a noise, its flow field the noise's normal map turned 90 degrees; the cylinder is turned on a lathe (the mapping's u, the default tangent); the ball (Ashikhmin-Shirley's model) is brushed round its poles." "
t_noise -s 256 -f 3 -S 5 --tile | t_filter normal --strength 30 |
    t_apply '$here/brushed_steel.scene' -s ${s}x$((2 * s / 3)) -q -o fig.exr"
figure satin "Anisotropic reflection: satin, Ashikhmin-Shirley's model over a dyed dielectric. The cushion's threads run round its tube, its sheen a band round the ring; the cloth is a satin weave whose weft floats turn the tangent 90 degrees, so its threads glint in two directions." "
t_apply '$here/satin.scene' -s ${s}x$((2 * s / 3)) -q -o fig.exr"
figure 2.9 "Section 2.9: hypertexture (Perlin and Hoffert), ray-marched: a fireball glowing through turbulence, an eroded sphere whose soft region fBm eats into, and smoke rising over a CSG block, lit through the volume." "
for sc in fireball eroded_sphere smoke_csg; do
    t_apply '$here/'\$sc.scene -s ${s}x$((3 * s / 4)) -q -o \$sc.exr
done
t_tile --matrix cycle --nu 3 --nv 1 -s $((3 * s))x$((3 * s / 4)) fireball.exr eroded_sphere.exr smoke_csg.exr -o fig.exr"
echo "wrote $page"
