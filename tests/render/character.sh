#!/usr/bin/env bash
# Thesis 4.4, items 6-8: surfaces described by their optical character, and the check of
# the energy balance (t_apply --check-energy).
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
    t_apply --check-energy "$T/c_$c.scene" -o "$T/c.exr" 2>"$T/e" && ! grep -q "breaks energy" "$T/e" ||
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
t_apply -q --check-energy "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
[ ! -s "$T/e" ] && ok "-q silences the check's warnings" || notok "-q and --check-energy"
t_apply --check-energy "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
[ "$(grep -c "surface 's' breaks energy: Kd + Ks + Kr + Kt reaches 1.4" "$T/e")" = 1 ] &&
    ok "--check-energy: one warning naming the surface and its sum" || notok "energy warning" "$(cat "$T/e")"
t_apply "$T/over.scene" -o "$T/x.exr" 2>"$T/e"
! grep -q "breaks energy" "$T/e" && ok "without --check-energy, no such warning" || notok "energy warning by default"
cat >"$T/tex.scene" <<S
image 16 12
camera { eye 0 1.5 -5 look 0 0.6 0 fov 45 }
light point { position 4 6 -5 }
texture t noise { solid }
surface s { Kd 0.7 Ks 0 apply t { mapping solid Ks = f } }
sphere { centre 0 1 0 radius 1 surface s }
S
t_apply --check-energy "$T/tex.scene" -o "$T/x.exr" 2>"$T/e"
grep -q "reaches 1.7" "$T/e" && ok "--check-energy follows a texture that sets Ks (0.7 + f up to 1)" ||
    notok "textured energy" "$(cat "$T/e")"
