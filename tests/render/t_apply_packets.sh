#!/bin/bash
# t_apply's packets of eye rays (render.c): a packet render equals the pixel-by-pixel
# render (TEXTURA_PACKETS=0) byte for byte, at any thread count, on scenes whose
# primitives are evaluated at hit points in batches: solid (eval3) and 2D (eval2)
# primitives, band-limited solids (through each hit's footprint), region ids at points, a texture applied twice, more applied textures than
# a packet looks up ahead, bumps, blended surfaces, area lights and jittered samples,
# spectral colour, image sizes that packets do not divide, and regions of the image; plain
# surfaces shaded together; samples on 2x2 and 3x3 grids (a packet's cells, camera.c).
. tests/lib.sh

cat >"$T/a.scene" <<'SCENE'
image 45 37
samples 1
depth 3
ambient 0.4 0.4 0.4
background 0.2 0.3 0.5
camera { eye 0 2.5 -6 look 0 0.8 0 fov 55 }
light point { position -4 7 -5 falloff 1 0.02 0.002 }
light spot { position 4 6 -4 at 0 0.5 0 angle 30 exponent 4 intensity 0.6 }
light area { position 2 6 -3 edge1 1 0 0 edge2 0 0 1 samples 2 intensity 0.4 }
texture veins turbulence { solid frequency 2 octaves 5 seed 3 }
texture cells noise { solid frequency 7 seed 9 }
texture flat noise { frequency 5 seed 4 }
texture ids checker { nu 4 nv 4 ids }
texture rings wood { solid rings 6 turbulence 0.05 frequency 2 octaves 3 seed 5 tilt 90 }
texture fine turbulence { solid frequency 9 octaves 6 seed 8 band_limit 1 }
texture hills fractal { solid mode fbm frequency 5 octaves 7 band_limit 1 }
surface other { Kd 0.2 0.6 0.3 Ks 0.3 n 20 apply cells { mapping solid Kd = f*p }
    apply fine { mapping solid Ks = f } }
surface marble { Ka 0.15 Kd 0.9 Ks 0.6 n 60 Kr 0.2 blend other
    apply veins { mapping solid Kd = palette(marble, 0.5 + 0.5 * sin(6 * ox + 12 * f)) }
    apply veins { mapping solid scale 3 bump = 0.2 }
    apply cells { mapping solid blend = f } }
surface oak { Ka 0.15 Kd 0.7 Ks 0.3 n 20 apply rings { mapping solid Kd = palette(wood, f) }
    apply hills { mapping solid Kd = 0.4 * p + 0.6 * f * p } apply fine { mapping solid bump = 0.1 } }
surface boxy { Kd 0.7 0.7 0.7 apply flat { mapping natural Kd = f*p + 0.1 }
    apply ids { mapping natural Kr = f / 20 region 3 { Kd = 1 0 0 } } }
surface many { Kd 0.5 0.5 0.5
SCENE
# ten textures on one surface: more than the packet looks up ahead
for i in 1 2 3 4 5 6 7 8 9 10; do
    echo "    apply cells { mapping solid scale $i Kd = 0.5*p + 0.05*f }" >>"$T/a.scene"
done
cat >>"$T/a.scene" <<'SCENE'
}
plane { surface boxy }
difference { sphere { centre 0 1 0 radius 1 } box { min -0.2 1 -1.2 max 1.2 2.2 0.2 }
             surface marble translate -2 0 0 }
cylinder { base 0 0 0 top 0 2 0 radius 0.6 surface oak }
box { min 1.4 0 -0.5 max 2.6 1.2 0.7 surface many }
sphere { centre 0.5 2.7 0.5 radius 0.4 surface boxy }
SCENE

render() { # NAME PACKETS ARGS...: the render as PFM (raw floats)
    local name=$1 p=$2
    shift 2
    TEXTURA_PACKETS=$p t_apply "$T/a.scene" -q -o "$T/$name.pfm" "$@"
}
for cfg in "spp1|--spp 1" "spp4|--spp 4" "spectral|--spectral 6 --spp 2" \
    "region|--region 5,3,27,22 --spp 2" "region1|--region 5,3,27,22" "odd|-s 33x17 --spp 3" \
    "spp9|-s 24x16 --spp 9"; do
    name=${cfg%%|*} args=${cfg#*|}
    # shellcheck disable=SC2086
    if render "$name-px" 0 -j 1 $args && render "$name-pk1" 1 -j 1 $args &&
        render "$name-pk2" 1 -j 2 $args && render "$name-px2" 0 -j 2 $args; then
        cmp -s "$T/$name-px.pfm" "$T/$name-pk1.pfm" &&
            ok "$name: packets give the pixel-by-pixel render's bytes" ||
            notok "$name: packets against pixel by pixel" "$(maxdiff "$T/$name-px.pfm" "$T/$name-pk1.pfm")"
        cmp -s "$T/$name-pk1.pfm" "$T/$name-pk2.pfm" && cmp -s "$T/$name-px.pfm" "$T/$name-px2.pfm" &&
            ok "$name: the same bytes with -j 1 and -j 2, packets or not" ||
            notok "$name: -j 1 against -j 2"
    else
        notok "$name: renders"
    fi
done
# packets beside the bounded objects' box trace the unbounded ones alone (render.c): a wide
# view, most of whose packets lie beside the box, and an eye inside the box, where none can
# be culled
for v in "wide|eye 0 9 -14 look 0 1 0 fov 100" "inside|eye 1 2 0 look -2 0.8 0 fov 90"; do
    name=${v%%|*}
    sed "s/^camera.*/camera { ${v#*|} }/" "$T/a.scene" >"$T/$name.scene"
    if TEXTURA_PACKETS=0 t_apply "$T/$name.scene" -q -j 1 -o "$T/$name-px.pfm" &&
        TEXTURA_PACKETS=1 t_apply "$T/$name.scene" -q -j 2 -o "$T/$name-pk.pfm"; then
        cmp -s "$T/$name-px.pfm" "$T/$name-pk.pfm" &&
            ok "$name view: packets give the pixel-by-pixel render's bytes" ||
            notok "$name view: packets against pixel by pixel" \
                "$(maxdiff "$T/$name-px.pfm" "$T/$name-pk.pfm")"
    else
        notok "$name view: renders"
    fi
done
# an area light of 4x4 samples, made four a vector from the jitters drawn first
# (whitted.c's area_lanes), with a falloff, against the pixel-by-pixel render's one by one
sed 's/^light area.*/light area { position 2 6 -3 edge1 1 0 0 edge2 0 0 1 samples 4 falloff 1 0.05 0.01 intensity 0.4 }/' \
    "$T/a.scene" >"$T/area4.scene"
if grep -q 'samples 4 falloff' "$T/area4.scene" &&
    TEXTURA_PACKETS=0 t_apply "$T/area4.scene" -q -j 1 -s 24x16 --spp 2 -o "$T/area4-px.pfm" &&
    TEXTURA_PACKETS=1 t_apply "$T/area4.scene" -q -j 2 -s 24x16 --spp 2 -o "$T/area4-pk.pfm"; then
    cmp -s "$T/area4-px.pfm" "$T/area4-pk.pfm" &&
        ok "an area light's 16 samples: packets give the pixel-by-pixel render's bytes" ||
        notok "an area light's 16 samples: packets against pixel by pixel" \
            "$(maxdiff "$T/area4-px.pfm" "$T/area4-pk.pfm")"
else
    notok "an area light's 16 samples: renders"
fi
# a packet tests only the objects whose boxes its pixels' rays can meet (tex_view_objects):
# 150 spheres and 50 boxes of the scene's surfaces over the view, large and small ones at
# the edges of packets (a box's top edge is its rect's), more than the 63 a packet keeps
# apart (the rest always tested: packets that meet none of those 63 still meet them)
{
    sed '/^plane\|^difference\|^ *surface marble translate\|^cylinder\|^box\|^sphere/d' \
        "$T/a.scene"
    echo "plane { surface boxy }"
    for i in $(seq 0 199); do
        x=$(((i % 9) - 4)).$((i % 7)) y=$((i / 9 % 3)).$((i % 5)) z=$((i / 20))
        sf=$(echo boxy marble oak many | cut -d' ' -f$((i % 4 + 1)))
        if [ $((i % 4)) = 3 ]; then
            echo "box { min $x $y $z max $(echo "$x $y $z" | awk '{ print $1 + 0.4, $2 + 0.3, $3 + 0.5 }')" \
                "surface $sf }"
        else
            echo "sphere { centre $x $y $z radius 0.$((i % 4 + 1))$((i % 3)) surface $sf }"
        fi
    done
    echo "box { min -5 0 9 max 5 0.2 9.3 surface oak }"
} >"$T/crowd.scene"
[ "$(grep -c '^sphere\|^box' "$T/crowd.scene")" = 201 ] &&
    TEXTURA_PACKETS=0 t_apply "$T/crowd.scene" -q -j 1 -s 61x47 -o "$T/crowd-px.pfm" &&
    TEXTURA_PACKETS=1 t_apply "$T/crowd.scene" -q -j 2 -s 61x47 -o "$T/crowd-pk.pfm" &&
    cmp -s "$T/crowd-px.pfm" "$T/crowd-pk.pfm" &&
    ok "201 objects over the view: packets give the pixel-by-pixel render's bytes" ||
    notok "201 objects: packets against pixel by pixel" \
        "$(maxdiff "$T/crowd-px.pfm" "$T/crowd-pk.pfm" 2>&1)"
# image maps, looked up ahead over a packet (a surface's first texture: footprints and
# trilinear lookups in vector lanes where the CPU has AVX-512): grey and colour maps of
# sides that are not powers of two, windows and repeats, affine mappings (a plane's, world,
# solid) and others (the natural mappings of a sphere, a CSG box, a tilted cylinder and a
# cone, sides and caps, a cylinder projection),
# bump maps (the tilt made ahead where the mapping is affine), maps on two tilted planes
# (one windowed: hits outside the window; one bumped), a map after
# a map, a surface's one map whose functions set a colour, scalars and (not a polynomial)
# Kr, or a colour and a bump (the slab: apply_direct bends the normal); a camera looking
# straight down; each render against pixel by pixel, packets at every SIMD level
awk 'BEGIN { print "P2 37 23 255"; for (y = 0; y < 23; y++) { l = "";
    for (x = 0; x < 37; x++) l = l " " int(128 + 120 * sin(x * 0.7) * cos(y * 0.45)); print l } }' \
    >"$T/grey.pgm"
awk 'BEGIN { print "P3 30 17 255"; for (y = 0; y < 17; y++) for (x = 0; x < 30; x++)
    print (x * 8) % 256, (y * 15) % 256, ((x + y) * 37) % 256 }' >"$T/colour.ppm"
cat >"$T/m.scene" <<SCENE
image 41 33
samples 1
depth 2
ambient 0.3 0.3 0.3
camera { eye 0 6 0 look 0 0 0 up 0 0 1 fov 70 }
light point { position -3 8 -4 }
texture grey file "$T/grey.pgm"
texture colour file "$T/colour.ppm"
surface floor { Kd 0.8 0.8 0.8 Ks 0.2 n 10
    apply grey { mapping natural repeat 3 2 Kd = 0.8*f + 0.1 bump = 0.2 }
    apply colour { mapping planar scale 0.3 Ks = f } }
surface ball { Kd 0.9 0.5 0.3 apply colour { mapping natural window 0.1 0.1 0.9 0.8 Kd = f*p } }
surface cube { Kd 0.6 0.6 0.6 Kr 0.3 apply colour { mapping natural repeat 2 2 Kd = f bump = 0.5 } }
surface can { Kd 0.5 0.7 0.5 apply grey { mapping cylinder repeat 4 1 Kd = f*p + 0.1 } }
surface rock { Kd 0.7 0.7 0.7 Ks 0.1 n 10
    apply colour { mapping solid scale 0.7 Kd = f Ks = 0.5*f n = 10 + 30*f Kr = 0.1*sin(9*f) } }
surface haze { Kd 0.7 0.7 0.7 apply grey { mapping world scale 0.5 Ka = f Kd = p*f bump = -0.4 }
    apply colour { mapping solid scale 0.3 Kd = f*p } }
surface slab { Kd 0.8 0.6 0.5 apply grey { mapping world scale 0.6 Kd = 0.7*f + 0.2 bump = 0.3 } }
surface tile { Kd 0.6 0.6 0.6 apply colour { mapping planar scale 0.7 window 0.2 0.1 0.8 0.7
    Kd = f*p + 0.2 } }
surface tile2 { Kd 0.5 0.7 0.5 apply grey { mapping natural repeat 2 3 Kd = 0.9*f bump = 0.3 } }
surface band { Kd 0.6 0.6 0.6 apply colour { mapping natural repeat 3 1 Kd = f*p + 0.1 } }
surface rim { Kd 0.6 0.6 0.6 apply grey { mapping natural window 0 0.2 1 0.9 Kd = f bump = 0.4 } }
plane { surface floor }
plane { surface tile rotate 25 0 -15 translate 0 0.4 0 }
plane { surface tile2 rotate -20 0 30 translate 0 0.6 0 }
sphere { centre -2 1 1 radius 1 surface ball }
difference { box { min -1 0 -1 max 1 2 1 } sphere { centre 1 2 -1 radius 0.8 } surface cube
             rotate 0 30 0 translate 2 0 1.5 }
cylinder { base 0 0 0 top 0 1.5 0 radius 0.6 surface can translate 0.5 0 -2 }
sphere { centre -2 0.7 -2 radius 0.7 surface rock }
box { min -0.5 0 -0.5 max 0.5 0.8 0.5 surface haze translate 2.5 0 -2.5 }
box { min -0.7 0 -0.5 max 0.7 0.3 0.5 surface slab translate -0.3 0 2.6 }
cylinder { base 0 0 0 top 0 1.6 0 radius 0.4 surface band rotate 0 0 12 translate -0.9 0 -0.3 }
cone { base 0 0 0 top 0 1.4 0 radius1 0.5 radius2 0.15 surface rim translate 0.9 0 0.2 }
SCENE
TEXTURA_PACKETS=0 t_apply "$T/m.scene" -q -j 1 -o "$T/m-px.pfm" &&
    TEXTURA_PACKETS=1 t_apply "$T/m.scene" -q -j 2 -o "$T/m-pk.pfm" &&
    TEXTURA_SIMD=avx2 t_apply "$T/m.scene" -q -j 1 -o "$T/m-pk2.pfm" &&
    TEXTURA_SIMD=scalar t_apply "$T/m.scene" -q -j 1 -o "$T/m-pk0.pfm" &&
    TEXTURA_PACKETS=1 t_apply "$T/m.scene" -q -j 1 --spp 4 -s 23x19 -o "$T/m4-pk.pfm" &&
    TEXTURA_PACKETS=0 t_apply "$T/m.scene" -q -j 1 --spp 4 -s 23x19 -o "$T/m4-px.pfm" ||
    notok "image maps: renders"
for v in pk pk2 pk0; do
    cmp -s "$T/m-px.pfm" "$T/m-$v.pfm" &&
        ok "image maps looked up ahead ($v): the pixel-by-pixel render's bytes" ||
        notok "image maps looked up ahead ($v) against pixel by pixel" \
            "$(maxdiff "$T/m-px.pfm" "$T/m-$v.pfm")"
done
cmp -s "$T/m4-px.pfm" "$T/m4-pk.pfm" && ok "image maps at 4 spp: packets give the same bytes" ||
    notok "image maps at 4 spp: packets against pixel by pixel" \
        "$(maxdiff "$T/m4-px.pfm" "$T/m4-pk.pfm")"
# the floor with its first map alone, and no tilted plane above it: its hits go in lanes
# from end to end (tex_prefetch_lanes), the one below the eye, seen head-on, the usual way
# (at 9x7 its footprint spans many texels)
sed '/apply colour { mapping planar scale 0.3 Ks = f } }/d; s/bump = 0.2 }$/bump = 0.2 } }/
    /^plane { surface tile/d' "$T/m.scene" >"$T/m1.scene"
[ "$(grep -c '^plane' "$T/m1.scene")" = 1 ] && ! grep -q 'Ks = f } }' "$T/m1.scene" &&
    ok "the floor's variant has one plane, of one map" ||
    notok "the floor's variant has one plane, of one map" "$(grep -n 'plane\|Ks = f' "$T/m1.scene")"
for s in 41x33 9x7; do
    TEXTURA_PACKETS=0 t_apply "$T/m1.scene" -q -j 1 -s $s -o "$T/m1-px.pfm" &&
        TEXTURA_PACKETS=1 t_apply "$T/m1.scene" -q -j 2 -s $s -o "$T/m1-pk.pfm" &&
        cmp -s "$T/m1-px.pfm" "$T/m1-pk.pfm" &&
        ok "a floor of one map in lanes, $s: the same bytes" ||
        notok "a floor of one map in lanes, $s, against pixel by pixel" \
            "$(maxdiff "$T/m1-px.pfm" "$T/m1-pk.pfm")"
done
# plain surfaces (Phong without a blend, Kr or Kt) in an RGB scene of point and spot lights:
# a packet shades their hits together, light by light (render.c's plain_shade); falloffs,
# spot cones of whole and fractional exponents, whole and fractional highlights, a map's
# window (hits outside it), two Kd functions, a CSG hollow and the inside of a sphere around
# it all (normals turned to the eye), solid textures of Kd, Ks and n with a bump (the general
# path's materials and bent normals), shadows, a mirror and a textured Kr beside them (shaded
# one by one) and the mirror's reflections of them
cat >"$T/p.scene" <<SCENE
image 41 33
samples 1
depth 3
ambient 0.3 0.3 0.3
camera { eye 0 3 -6 look 0 0.8 0 fov 70 }
light point { position -3 8 -4 }
light point { position 3 5 -6 falloff square intensity 40 }
light spot { position 2 6 -3 at 0 0.5 0 angle 35 exponent 3 intensity 0.7 }
light spot { position -2 4 -5 at 0 0 0 angle 20 exponent 2.5 falloff 1 0.02 0.002 }
texture grey file "$T/grey.pgm"
surface floor { Kd 0.8 0.8 0.8 apply grey { mapping natural repeat 3 2 Kd = 0.8*f + 0.1
    Kd = 0.5*p + 0.4*f*p } }
surface shiny { Kd 0.2 0.3 0.8 Ks 0.8 n 40.5 }
surface dull { Kd 0.6 0.5 0.4 Ks 0.3 n 12 apply grey { mapping natural window 0.1 0.1 0.9 0.8
    Kd = f*p } }
surface mirror { Kd 0.3 0.3 0.3 Ks 0.5 n 30 Kr 0.5 }
surface dome { Kd 0.5 0.6 0.7 Ks 0.2 n 8 }
texture veins turbulence { solid frequency 2 octaves 4 seed 3 }
texture cells noise { solid frequency 7 seed 9 }
surface bumpy { Kd 0.7 0.6 0.5 Ks 0.4 n 25 apply veins { mapping solid Kd = f*p bump = 0.3 }
    apply cells { mapping solid Ks = f n = 10 + 20*f } }
surface glint { Kd 0.6 0.6 0.3 apply cells { mapping solid Kd = f*p Kr = 0.3*f } }
plane { surface floor }
difference { box { min -1 0 -1 max 1 2 1 } sphere { centre 0 1 0 radius 1.3 } surface dull
             rotate 0 20 0 translate -2 0 0 }
sphere { centre 0.4 1 0.5 radius 0.8 surface shiny }
cylinder { base 0 0 0 top 0 1.8 0 radius 0.5 surface mirror translate 2 0 0 }
sphere { centre 0 0 0 radius 40 surface dome }
box { min -0.6 0 -0.6 max 0.6 0.9 0.6 surface bumpy rotate 0 30 0 translate 1.2 0 -2 }
sphere { centre -1 0.4 -2.2 radius 0.4 surface glint }
SCENE
for args in "-j 1" "-j 2" "-j 1 --spp 4 -s 23x19"; do
    # shellcheck disable=SC2086
    TEXTURA_PACKETS=0 t_apply "$T/p.scene" -q $args -o "$T/p-px.pfm" &&
        TEXTURA_PACKETS=1 t_apply "$T/p.scene" -q $args -o "$T/p-pk.pfm" &&
        TEXTURA_SIMD=scalar t_apply "$T/p.scene" -q $args -o "$T/p-pk0.pfm" &&
        cmp -s "$T/p-px.pfm" "$T/p-pk.pfm" && cmp -s "$T/p-px.pfm" "$T/p-pk0.pfm" &&
        ok "plain surfaces shaded together ($args): the pixel-by-pixel render's bytes" ||
        notok "plain surfaces shaded together ($args) against pixel by pixel" \
            "$(maxdiff "$T/p-px.pfm" "$T/p-pk.pfm")"
done
sd=$(info_json "$T/p-pk.pfm" stats 0 stddev)
awk -v s="$sd" 'BEGIN { exit !(s > 0.05) }' &&
    ok "the plain scene is lit and textured (stddev $sd)" ||
    notok "the plain scene is lit and textured" "stddev $sd"
sd=$(info_json "$T/m-pk.pfm" stats 0 stddev)
awk -v s="$sd" 'BEGIN { exit !(s > 0.05) }' && ok "the maps' scene is textured (stddev $sd)" ||
    notok "the maps' scene is textured" "stddev $sd"
# the scene is not flat: the textures show (else the comparison would prove little)
sd=$(info_json "$T/spp1-pk1.pfm" stats 0 stddev)
awk -v s="$sd" 'BEGIN { exit !(s > 0.02) }' && ok "the test scene's textures vary (stddev $sd)" ||
    notok "the test scene is textured" "stddev $sd"
# a packet's shadow rays traced together through the tree, light by light
# (tex_scene_transmit_n): the light through nested and overlapping glass (Kt multiplied
# at every crossing, in each ray's own order), a glass CSG shell, 40 small spheres in the
# tree (more than one leaf: shadow rays batch), four lights with a 3x3 area light (12
# samples a hit, the general path's batches) and with a 6x6 one (39: more than a hit keeps,
# each shadow ray on its own), and the point and spot lights alone (the plain hits' batches)
{
    cat <<SCENE
image 37 29
samples 1
depth 3
ambient 0.2 0.2 0.2
camera { eye 0 3 -6 look 0 0.7 0 fov 60 }
light point { position -3 8 -4 }
light spot { position 3 6 -3 at 0 0.5 0 angle 35 exponent 2 intensity 0.6 }
light distant { direction -0.3 1 -0.5 intensity 0.3 }
light area { position -1 6 -2 edge1 2 0 0 edge2 0 0 2 samples 3 intensity 0.5 }
texture cells noise { solid frequency 5 seed 9 }
surface floor { Kd 0.8 0.8 0.8 apply cells { mapping solid Kd = f*p + 0.1 } }
surface glass { Kd 0.05 Ks 0.5 n 80 Kt 0.7 ior 1.3 }
surface tint { Kd 0.1 0.3 0.1 Kt 0.5 ior 1.1 }
surface red { Kd 0.8 0.2 0.1 Ks 0.3 n 20 }
plane { surface floor }
sphere { centre 0 1.2 0 radius 1 surface glass }
sphere { centre 0 1.2 0 radius 0.5 surface tint }
sphere { centre 0.8 1.4 0.3 radius 0.6 surface tint }
difference { box { min -1 0 -1 max 1 1.5 1 } box { min -0.8 0.2 -0.8 max 0.8 1.7 0.8 }
             surface glass translate -2.2 0 0.5 }
SCENE
    for i in $(seq 0 39); do
        echo "sphere { centre $((i % 8 - 4)).$((i % 3))5 0.15 $((i / 8 - 1)).$((i % 5))"\
            "radius 0.15 surface $(echo red tint | cut -d' ' -f$((i % 2 + 1))) }"
    done
} >"$T/s.scene"
sed 's/samples 3 intensity/samples 6 intensity/' "$T/s.scene" >"$T/s6.scene"
sed '/^light distant\|^light area/d' "$T/s.scene" >"$T/sp.scene"
for sc in s s6 sp; do
    for args in "-j 1" "-j 2 --spp 3"; do
        # shellcheck disable=SC2086
        TEXTURA_PACKETS=0 t_apply "$T/$sc.scene" -q -j 1 ${args#-j ?} -o "$T/$sc-px.pfm" &&
            TEXTURA_PACKETS=1 t_apply "$T/$sc.scene" -q $args -o "$T/$sc-pk.pfm" &&
            cmp -s "$T/$sc-px.pfm" "$T/$sc-pk.pfm" &&
            ok "shadow rays together ($sc.scene $args): the pixel-by-pixel render's bytes" ||
            notok "shadow rays together ($sc.scene $args) against pixel by pixel" \
                "$(maxdiff "$T/$sc-px.pfm" "$T/$sc-pk.pfm" 2>&1)"
    done
done
# the glass passes part of the light: with one light behind the glass, its shadow falls
# on the floor before it (the image's bottom rows, PFM's first) lighter than opaque spheres'
cat >"$T/s1.scene" <<SCENE
$(sed '/^light\|^sphere { centre [-0-9.]* 0.15/d' "$T/s.scene")
light point { position 0 8 5 }
SCENE
sed 's/surface glass }/surface red }/; s/surface tint }/surface red }/g' "$T/s1.scene" >"$T/s1r.scene"
if t_apply "$T/s1.scene" -q -o "$T/s1.pfm" && t_apply "$T/s1r.scene" -q -o "$T/s1r.pfm"; then
    d=$(python3 -c '
import sys
def rd(p):
    f = open(p, "rb"); f.readline(); w, h = map(int, f.readline().split()); f.readline()
    import array; a = array.array("f"); a.frombytes(f.read()); return w, h, a
w, h, a = rd(sys.argv[1]); _, _, b = rd(sys.argv[2])
s = sum(a[i] - b[i] for i in range(3 * w * (h // 4)))
print("%.4f" % s)' "$T/s1.pfm" "$T/s1r.pfm")
    awk -v d="$d" 'BEGIN { exit !(d > 0) }' &&
        ok "glass lets light through to the floor where opaque spheres do not (sum $d)" ||
        notok "glass lets light through to the floor" "sum $d"
else
    notok "the glass shadow scenes render"
fi
