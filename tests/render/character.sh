#!/usr/bin/env bash
# Thesis 4.4, items 6-8: surfaces described by their optical character, and the check of
# the energy balance (t_apply's --check-energy, on by default).
. "$(dirname "$0")/../lib.sh"
scene() { # NAME SURFACE-WORDS: a sphere on a plane, both of that surface
    cat >"$T/$1.scene" <<S
image 48 36
ambient 0.2 0.2 0.2
camera { eye 0 1.5 -5 look 0 0.6 0 fov 45 }
light point { position 4 6 -5 }
surface s { $2 }
plane { surface s }
sphere { centre 0 1 0 radius 1 surface s }
S
}
# every character of the registry: the same picture as its words written out, and within
# the energy balance
bad="" n=0
for c in $(t_apply --help-scene surface | awk '$1 == "character" { gsub(/\|/, " ", $2); print $2 }'); do
    words=$(awk -v c="$c" '$0 ~ "\\{\"" c "\", \\{" { f = 1 } f { print } f && /\}\}\},/ { exit }' \
        "${TEXTURA_TOP:-.}/libtex/render/render_params.c" | grep -o '{"[A-Za-z]*", "[0-9.]*"}' |
        sed 's/{"\([A-Za-z]*\)", "\([0-9.]*\)"}/\1 \2/' | tr '\n' ' ')
    scene "c_$c" "character $c"
    scene "w_$c" "$words"
    t_apply -q "$T/c_$c.scene" -o "$T/c.exr" && t_apply -q "$T/w_$c.scene" -o "$T/w.exr" &&
        [ "$(maxdiff "$T/c.exr" "$T/w.exr")" = 0 ] || bad="$bad $c(render)"
    t_apply "$T/c_$c.scene" -o "$T/c.exr" 2>"$T/e" && ! grep -q "breaks energy" "$T/e" ||
        bad="$bad $c(energy)"
    n=$((n + 1))
done
[ "$n" -ge 5 ] && [ -z "$bad" ] &&
    ok "each of $n characters renders as its words written out, within the energy balance" ||
    notok "characters" "$n; wrong:$bad"
# words given beside a character win, whatever their order
scene cw "Kd 1 0 0 character glossy n 10"
scene ww "Ka 0.1 Kd 1 0 0 Ks 0.4 n 10 Kr 0 Kt 0"
t_apply -q "$T/cw.scene" -o "$T/a.exr" && t_apply -q "$T/ww.scene" -o "$T/b.exr"
same "a surface's own words win over its character's" "$T/a.exr" "$T/b.exr"
scene bad "character glosy"
check_fails "an unknown character" 2 t_apply "$T/bad.scene" -o "$T/x.exr"
grep -q "did you mean glossy" "$T/.err" && ok "... names the nearest" || notok "character typo" "$(cat "$T/.err")"
# the check: a surface's own values, and its textures'
scene over "Kd 0.9 Ks 0.5 n 20"
t_apply -q "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
[ ! -s "$T/e" ] && ok "-q silences the check's warnings" || notok "-q and the check" "$(cat "$T/e")"
t_apply "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
[ "$(grep -c "surface 's' breaks energy: Kd + max(Ks, Kr) + Kt reaches 1.4" "$T/e")" = 1 ] &&
    ok "by default: one warning naming the surface and its sum" || notok "energy warning" "$(cat "$T/e")"
t_apply --check-energy off "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
! grep -q "breaks energy" "$T/e" && ok "--check-energy off: no such warning" || notok "--check-energy off"
t_apply --check-energy "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
grep -q "breaks energy" "$T/e" && ok "--check-energy alone: the warning" || notok "--check-energy alone"
# Ks and Kr are one specular reflectance: the larger counts; Kt adds
energy() { # WHAT SURFACE-WORDS EXPECTED-SUM|none
    scene en "$2"
    t_apply "$T/en.scene" -o "$T/x.exr" 2>"$T/e"
    if [ "$3" = none ]; then
        ! grep -q "breaks energy" "$T/e" && ok "energy: $1" || notok "energy: $1" "$(cat "$T/e")"
    else
        grep -q "reaches $3, above 1" "$T/e" && ok "energy: $1 ($3)" || notok "energy: $1" "$(cat "$T/e")"
    fi
}
energy "Ks beside an equal Kr counts once" "Kd 0.5 Ks 0.5 n 20 Kr 0.5" none
energy "the larger of Ks and Kr counts" "Kd 0.5 Ks 0.2 n 20 Kr 0.6" 1.1
energy "Kt adds" "Kd 0.3 Ks 0.3 n 20 Kr 0.3 Kt 0.5" 1.1
# Cook-Torrance as it shades: (1 - s) Kd + max(s, Kr, Kt); a conductor's Kt does not count
energy "Cook-Torrance dielectric" "Kd 0.8 Kr 1 Kt 1 model cook-torrance material bk7 specular 0.9" 1.08
energy "Cook-Torrance conductor, s = 1" "Kd 0.9 Ks 0.9 Kr 0.8 Kt 0.5 model cook-torrance material gold specular 1" none
energy "Ward, as Cook-Torrance" "Kd 0.9 Kr 0.9 model ward material gold specular 0.5" 1.35
energy "Cook-Torrance diffuse beside Kr" "Kd 0.9 Kr 0.9 model cook-torrance material gold specular 0.5" 1.35
grep -q "(1 - s) Kd + max(s, Kr, Kt) reaches 1.35" "$T/e" && ok "... the message names Cook-Torrance's sum" ||
    notok "Cook-Torrance's message" "$(cat "$T/e")"
# every scene the project ships is within the balance (a map on standard input for those
# that read one)
bad=""
for f in "${TEXTURA_TOP:-.}"/patterns/*.scene "${TEXTURA_TOP:-.}"/tests/scenes/*.scene; do
    t_noise -s 16 | t_apply "$f" -s 8x6 --spp 1 -o "$T/x.exr" 2>"$T/e"
    grep -q "breaks energy" "$T/e" && bad="$bad $(basename "$f")"
done
[ -z "$bad" ] && ok "every scene of patterns/ and tests/scenes within the energy balance" ||
    notok "scenes that break energy" "$bad"
cat >"$T/tex.scene" <<S
image 16 12
camera { eye 0 1.5 -5 look 0 0.6 0 fov 45 }
light point { position 4 6 -5 }
texture t noise { solid }
surface s { Kd 0.7 Ks 0 apply t { mapping solid Ks = f } }
sphere { centre 0 1 0 radius 1 surface s }
S
t_apply "$T/tex.scene" -o "$T/x.exr" 2>"$T/e"
grep -q "reaches 1.7" "$T/e" && ok "the check follows a texture that sets Ks (0.7 + f up to 1)" ||
    notok "textured energy" "$(cat "$T/e")"
