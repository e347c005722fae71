#!/bin/sh
# five_spheres.sh - the scene of Ferreira (1991), section 8 (five spheres on a checkered
# dielectric) rendered twice with the same camera, lights and surfaces:
# Whitted-Phong in RGB on the left, Cook-Torrance in the spectral colour model
# on the right, written side by side (see the discussion in t_apply(5)).
#
#   patterns/five_spheres.sh [-o PREFIX] [-s N|WxH] [-S SEED]   -> PREFIX_render
#                                               (each half WxH, default 800x600)
#
# Without Textura's composition tools (t_xform, t_op) the halves are joined with
# netpbm's pamcat.  The scene has no random texture: -S changes nothing.
recipe=five_spheres
size=${size:-800x600}
. "$(dirname "$0")/recipe.sh"
w=$W h=$H
# the floor's checks: a 2x2-check map, 64 px
awk 'BEGIN { print "P2 64 64 255"; for (y = 0; y < 64; y++) { l = "";
    for (x = 0; x < 64; x++) l = l " " ((int(x / 32) + int(y / 32)) % 2 ? 230 : 26); print l } }' \
    >"$tmp/checks.pgm"
# Cook-Torrance's coefficients read as Whitted's pass 1 (Kd beside a constant Kr): that
# excess is what the comparison shows, so its energy warning is not wanted here
t_apply "$here/five_spheres.scene" -s "$size" --rgb --model phong --check-energy off \
    -o "$tmp/rgb.png" <"$tmp/checks.pgm"
t_apply "$here/five_spheres.scene" -s "$size" -o "$tmp/spectral.png" <"$tmp/checks.pgm"
if command -v t_xform >/dev/null && command -v t_op >/dev/null; then
    # each half on a canvas twice as wide, moved to its side, then added
    t_xform --expand "$((2 * w))x$h" --shift "$((-w / 2)),0" -o "$tmp/l.exr" "$tmp/rgb.png"
    t_xform --expand "$((2 * w))x$h" --shift "$((w - w / 2)),0" -o "$tmp/r.exr" "$tmp/spectral.png"
    t_op add "$tmp/l.exr" "$tmp/r.exr" -o "$tmp/render.exr"
else
    pngtopam "$tmp/rgb.png" >"$tmp/l.pam"
    pngtopam "$tmp/spectral.png" >"$tmp/r.pam"
    pamcat -lr "$tmp/l.pam" "$tmp/r.pam" | pnmtopng >"$tmp/render.png"
    t_convert "$tmp/render.png" -o "$tmp/render.exr"
fi
write "$tmp/render.exr" render # left: Whitted-Phong, RGB; right: Cook-Torrance, spectral
