#!/bin/bash
# t_apply: the spectral colour model and Cook-Torrance in scenes (issue 10)
. tests/lib.sh
# scenes outside patterns/ find the shipped materials database through this
export TEXTURA_MATERIALS=patterns/materials.txt

# a metal sphere filling the view, reflecting a white (D65) sky: its colour is
# the metal's Fresnel reflectance (no lights, no ambient)
metal() {
    cat <<EOS
colour spectral 16
image 24 24
ambient 0 0 0
background 1 1 1
camera { eye 0 0 -5 look 0 0 0 fov 12 }
surface m { Kr 1 model cook-torrance material $1 facets beckmann 0.1 specular 1 }
sphere { radius 1 surface m }
EOS
}
mean() { info_json "$1" stats "$2" mean; }
for m in gold silver copper; do
    metal $m >"$T/$m.scene"
    check "a $m sphere renders in spectral mode" t_apply "$T/$m.scene" -o "$T/$m.exr"
done
r=$(mean "$T/gold.exr" 0) g=$(mean "$T/gold.exr" 1) b=$(mean "$T/gold.exr" 2)
awk -v r="$r" -v g="$g" -v b="$b" 'BEGIN { exit !(r > 1.4 * b && g > 1.15 * b && r >= g) }' &&
    ok "gold renders yellow (R $r G $g B $b)" || notok "gold renders yellow" "R $r G $g B $b"
r=$(mean "$T/silver.exr" 0) g=$(mean "$T/silver.exr" 1) b=$(mean "$T/silver.exr" 2)
awk -v r="$r" -v g="$g" -v b="$b" 'BEGIN { m = (r + g + b) / 3
    exit !(m > 0.5 && (r - b) / m < 0.08 && (b - r) / m < 0.08 && (g - b) / m < 0.08) }' &&
    ok "silver renders neutral (R $r G $g B $b)" || notok "silver renders neutral" "R $r G $g B $b"
r=$(mean "$T/copper.exr" 0) b=$(mean "$T/copper.exr" 2)
awk -v r="$r" -v b="$b" 'BEGIN { exit !(r > 1.5 * b) }' &&
    ok "copper renders reddish (R $r B $b)" || notok "copper renders reddish" "R $r B $b"

# a white diffuse plane under a D65 light is neutral; under illuminant A it is orange
lit() {
    cat <<EOS
colour spectral ${2:-16}
image 16 16
ambient 0 0 0
camera { eye 0 3 -3 look 0 0 0 }
light distant { direction 0 1 -1 spectrum $1 }
surface w { Ka 0 Kd 1 model cook-torrance specular 0 }
plane { surface w }
EOS
}
lit D65 >"$T/d65.scene"
lit A >"$T/a.scene"
lit D65 8 >"$T/d65_8.scene"
t_apply "$T/d65.scene" -o "$T/d65.exr" && t_apply "$T/a.scene" -o "$T/a.exr" &&
    t_apply "$T/d65_8.scene" -o "$T/d65_8.exr"
r=$(mean "$T/d65.exr" 0) g=$(mean "$T/d65.exr" 1) b=$(mean "$T/d65.exr" 2)
awk -v r="$r" -v g="$g" -v b="$b" 'BEGIN { m = (r + g + b) / 3
    exit !(m > 0.3 && (r - b) / m < 0.01 && (b - r) / m < 0.01 && (g - r) / m < 0.01 && (r - g) / m < 0.01) }' &&
    ok "a white plane under D65 is neutral grey (R $r G $g B $b)" ||
    notok "white plane under D65 is neutral" "R $r G $g B $b"
r8=$(mean "$T/d65_8.exr" 0)
approx "$r" "$r8" 0.01 && ok "8 and 16 bands agree on a white plane ($r, $r8)" ||
    notok "8 and 16 bands agree" "$r vs $r8"
r=$(mean "$T/a.exr" 0) b=$(mean "$T/a.exr" 2)
awk -v r="$r" -v b="$b" 'BEGIN { exit !(r > 1.5 * b) }' &&
    ok "the same plane under illuminant A is orange (R $r B $b)" || notok "under A" "R $r B $b"
sed 's/spectrum D65/spectrum blackbody 6500/' "$T/d65.scene" >"$T/bb.scene"
check "a blackbody light renders" t_apply "$T/bb.scene" -o "$T/bb.exr"
sed 's/colour spectral 16/colour rgb/' "$T/a.scene" >"$T/a_rgb.scene"
t_apply "$T/a_rgb.scene" -o "$T/a_rgb.exr"
r=$(mean "$T/a_rgb.exr" 0) b=$(mean "$T/a_rgb.exr" 2)
awk -v r="$r" -v b="$b" 'BEGIN { exit !(r > 1.5 * b) }' &&
    ok "an A light in an RGB scene is orange too (R $r B $b)" || notok "A in RGB" "R $r B $b"

# the seed scene: spectral with the scene's settings, and the overrides
awk 'BEGIN { print "P2 8 8 255"; for (y = 0; y < 8; y++) { l = "";
    for (x = 0; x < 8; x++) l = l " " ((int(x / 4) + int(y / 4)) % 2 ? 230 : 26); print l } }' \
    >"$T/checks.pgm"
seed=patterns/five_spheres.scene
check "five_spheres renders (Cook-Torrance, spectral)" \
    t_apply "$seed" -s 48x36 -o "$T/fs.exr" <"$T/checks.pgm"
check "five_spheres renders with --rgb --model phong" \
    t_apply "$seed" -s 48x36 --rgb --model phong -o "$T/fp.exr" <"$T/checks.pgm"
check "--spectral 4 overrides the scene" \
    t_apply "$seed" -s 48x36 --spectral 4 -o "$T/f4.exr" <"$T/checks.pgm"
cmp -s "$T/fs.exr" "$T/fp.exr" && notok "the two models differ" || ok "the two models differ"
for j in 1 2; do
    t_apply "$seed" -s 48x36 --spp 2 -j $j -o "$T/fj$j.exr" <"$T/checks.pgm" &&
        t_convert -o "$T/fj$j.pfm" "$T/fj$j.exr"
done
cmp -s "$T/fj1.pfm" "$T/fj2.pfm" && ok "spectral render: same bytes with -j 1 and -j 2" ||
    notok "spectral determinism across -j"

check_fails "--spectral 0 is refused" 2 t_apply "$T/d65.scene" --spectral 0 -o "$T/x.exr"
check_fails "--spectral 10000 is refused" 2 t_apply "$T/d65.scene" --spectral 10000 -o "$T/x.exr"
check_fails "--spectral with --rgb is refused" 2 t_apply "$T/d65.scene" --spectral 8 --rgb -o "$T/x.exr"
check_fails "unknown --model" 2 t_apply "$T/d65.scene" --model blinn -o "$T/x.exr"
[ -e "$T/x.exr" ] && notok "no output file after a refused option" || ok "no output after refused options"

# bad scenes: one line naming file:line:column, exit 2 (or 1), no output file
bad() {
    local name=$1 status=$2 text=$3
    printf '%s\n' "$text" >"$T/bad.scene"
    check_fails "$name" "$status" t_apply "$T/bad.scene" -o "$T/bad.png"
    if [ -e "$T/bad.png" ]; then notok "$name: no output file"; rm -f "$T/bad.png"; fi
    if ! grep -q "bad.scene:[0-9]*:[0-9]*:" "$T/.err"; then
        notok "$name: message names file:line:column" "$(cat "$T/.err")"
    fi
}
bad "colour spectral 0" 2 'colour spectral 0'
bad "colour spectral 10000" 2 'colour spectral 10000'
bad "colour model unknown" 2 'colour cmyk'
bad "unknown material" 2 $'surface s {\n  material unobtainium\n}'
grep -q "bad.scene:2:" "$T/.err" && ok "unknown material: the message gives its line" ||
    notok "unknown material line" "$(cat "$T/.err")"
bad "unknown facet distribution" 2 'surface s { facets gauss 0.2 }'
bad "Beckmann slope 0" 2 'surface s { facets beckmann 0 }'
bad "specular fraction above 1" 2 'surface s { specular 1.5 }'
bad "unknown illuminant" 2 'light distant { spectrum nosuch }'
bad "blackbody at 0 K" 2 'light distant { spectrum blackbody 0 }'
bad "colour and spectrum on one light" 2 'light distant { colour 1 0 0 spectrum D65 }'
bad "missing materials file" 1 'materials "/nonexistent/materials.txt"'
printf 'material glass2 dielectric\nior -1.5\nend\n' >"$T/neg.txt"
bad "materials file with n <= 0" 2 "materials \"$T/neg.txt\""
printf 'material m conductor\nnk 500 0.2 -3\nend\n' >"$T/k.txt"
bad "materials file with k < 0" 2 "materials \"$T/k.txt\""
printf 'material m conductor\nnk 600 0.2 3\nnk 500 0.2 3\nend\n' >"$T/uns.txt"
bad "materials file with unsorted wavelengths" 2 "materials \"$T/uns.txt\""

# another database through `materials FILE`
printf 'material mine dielectric\nsource test\nior 1.33\nend\n' >"$T/mine.txt"
printf 'materials "%s"\ncolour spectral 8\nimage 8 8\nsurface s { model cook-torrance material mine }\nsphere { radius 1 surface s }\n' \
    "$T/mine.txt" >"$T/mine.scene"
check "a scene reads its own materials file" t_apply "$T/mine.scene" -o "$T/mine.exr"
