# thesis_figures.sh - the thesis's composition figures rebuilt from the real primitives,
# as golden images (TEXTURA_REGOLD=1 rewrites them) and as properties.
. "$(dirname "$0")/../lib.sh"

# Fig. 5.9, cascade_circle_flower: as the thesis's code has it, region 1 of a circle (the
# outside, in Figure 5.2's numbering) filled with a flower.
t_circle -s 128 --ids -o "$T/circle_ids.exr"
t_flower -s 128 --petals 5 -o "$T/flower.exr"
t_cascade "$T/circle_ids.exr" 1="$T/flower.exr" --default '#204060' -o "$T/casc.exr"
golden "cascade_circle_flower golden (Fig. 5.9)" "$T/casc.exr" thesis_cascade_circle_flower.exr 1e-5
t_op mul "$T/flower.exr" 1 -o "$T/flower_copy.exr"
check "outside the circle (region 1) the cascade is the flower itself" python3 -c "
import subprocess, json
def px(path, x, y):
    out = subprocess.check_output(['t_convert', path, '--format', 'pfm'])
    head = out.split(b'\n', 3); w, h = map(int, head[1].split()); import struct
    nc = 3 if head[0] == b'PF' else 1
    row = h - 1 - y
    return struct.unpack_from('<%df' % nc, head[3], 4 * nc * (row * w + x))
assert px('$T/casc.exr', 2, 2) == px('$T/flower.exr', 2, 2)
assert px('$T/casc.exr', 64, 64) != px('$T/flower.exr', 64, 64)
"

# Fig. 5.8, diagonal_flower: a matrix of maps, a circle where u' = v', a flower elsewhere.
t_circle -s 64 -o "$T/c64.exr"
t_flower -s 64 --petals 4 -o "$T/f64.exr"
t_tile --matrix diagonal --nu 3 --nv 3 -s 192 -o "$T/diag.exr" "$T/c64.exr" "$T/f64.exr"
golden "diagonal_flower golden (Fig. 5.8)" "$T/diag.exr" thesis_diagonal_flower.exr 1e-5

# Fig. 5.10: turbulence applied to a stripe (domain perturbation): marble veins.
t_stripe -s 128 -o "$T/stripe.exr"
t_turbulence -s 128 -S 2 --tile -o "$T/turb.exr"
t_warp "$T/stripe.exr" "$T/turb.exr" --displacement 0.1 -o "$T/veins.exr"
golden "turbulence o stripe golden (Fig. 5.10)" "$T/veins.exr" thesis_turbulence_stripe.exr 1e-5
d=$(maxdiff "$T/veins.exr" "$T/stripe.exr")
awk -v d="$d" 'BEGIN { exit !(d > 0.2) }' && ok "the turbulence bends the stripes" || notok "the turbulence bends the stripes" "max diff $d"

# Figs. 5.11 and 5.12: stripe repetitions, plain and mirrored.
t_stripe -s 64 -a 30 -o "$T/s1.exr"
t_tile --nu 3 --nv 2 -s 192x128 -o "$T/rep.exr" "$T/s1.exr"
t_tile --nu 3 --nv 2 --mirror -s 192x128 -o "$T/mir.exr" "$T/s1.exr"
golden "stripe repetition golden (Fig. 5.11)" "$T/rep.exr" thesis_stripe_repeat.exr 1e-5
golden "mirrored stripe golden (Fig. 5.12)" "$T/mir.exr" thesis_stripe_mirror.exr 1e-5
