#!/usr/bin/env bash
# Composed primitives (lang/proc.h): t_expr, definitions files, scenes, scripts, errors.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
defs=$top/patterns/primitives.tp

# ---- one primitive through t_expr is that primitive ----
t_noise -s 96 -S 3 -f 5 -o "$T/n.exr"
t_expr 'noise(frequency = 5)' -s 96 -S 3 -o "$T/e.exr"
same "t_expr 'noise(frequency = 5)' is t_noise -f 5" "$T/n.exr" "$T/e.exr" 1e-6
t_turbulence -s 96 -S 2 -n 6 -o "$T/t.exr"
t_op mul "$T/t.exr" 4 | t_op add - 1 >"$T/t41.exr"
t_expr '4*turbulence(octaves = 6) + 1' -s 96 -S 2 -o "$T/e41.exr"
same "4*turbulence + 1 equals the t_turbulence | t_op pipeline" "$T/t41.exr" "$T/e41.exr" 1e-5
# coordinates given to a call move its domain: noise at (u + 1/8, v) is noise offset by one cell
t_noise -s 64 -S 3 -f 8 --offset 1,0 -o "$T/no.exr"
t_expr 'noise(u + 0.125, v, frequency = 8)' -s 64 -S 3 -o "$T/eo.exr"
same "noise(u + 1/8, v) is noise with --offset 1,0" "$T/no.exr" "$T/eo.exr" 1e-5
# seed = K adds K to the field's seed
t_noise -s 32 -S 7 -o "$T/s7.exr"
t_expr 'noise(seed = 4)' -s 32 -S 3 -o "$T/s34.exr"
same "seed = 4 inside a call adds to -S" "$T/s7.exr" "$T/s34.exr" 1e-6
# arithmetic and functions evaluated over rows agree with the formulas
t_expr 'u' -s 8x1 -o "$T/u.pfm"
approx "$(info_json "$T/u.pfm" stats 0 mean)" 0.5 1e-6 && ok "u is the pixel centre's coordinate" ||
    notok "u mean" "$(info_json "$T/u.pfm" stats 0 mean)"
t_expr 'clamp(-3 + 0*u, 0, 1) + smoothstep(0, 1, 0.5) + pow(2, 3)/16 + if(u > 2, 7, 0) + pi - pi' \
    -s 4 -o "$T/c.pfm"
approx "$(info_json "$T/c.pfm" stats 0 max)" 1 1e-6 && ok "constants fold: 0 + 0.5 + 0.5 + 0" ||
    notok "folded constants" "$(info_json "$T/c.pfm" stats 0 max)"

# ---- determinism ----
# (PFM: the pixels alone, without the history that records -j)
t_expr --defs "$defs" marble -s 200x120 -j 1 -o "$T/j1.pfm"
t_expr --defs "$defs" marble -s 200x120 -j 2 -o "$T/j2.pfm"
t_expr --defs "$defs" marble -s 200x120 -j 7 -o "$T/j7.pfm"
cmp -s "$T/j1.pfm" "$T/j2.pfm" && cmp -s "$T/j1.pfm" "$T/j7.pfm" &&
    ok "marble is byte-identical for -j 1, 2, 7" || notok "marble -j"
t_expr --defs "$defs" cracked -s 97 -j 1 -o "$T/c1.pfm"
t_expr --defs "$defs" cracked -s 97 -j 3 -o "$T/c3.pfm"
cmp -s "$T/c1.pfm" "$T/c3.pfm" && ok "cracked is byte-identical for -j 1, 3" || notok "cracked -j"
printf 'primitive s3(k = 1 in 0 to 9) = k*bubble(u, v, w, dimension = 3)\n' >"$T/s3.tp"
printf 'image 40 30\ncamera { eye 0 0 -3 look 0 0 0 fov 40 }\nlight point { position -3 4 -5 intensity 1 }\nprimitives "%s"\ntexture m s3 { solid }\nsurface s { Kd 0.9 apply m { mapping solid Kd = f } }\nsphere { centre 0 0 0 radius 1 surface s }\n' \
    "$T/s3.tp" >"$T/s3.scene"
t_apply "$T/s3.scene" -q -j 1 -o "$T/r1.pfm" && t_apply "$T/s3.scene" -q -j 2 -o "$T/r2.pfm" &&
    cmp -s "$T/r1.pfm" "$T/r2.pfm" && ok "a solid composed texture renders the same for -j 1, 2" ||
    notok "solid -j"

# ---- parameters from the declarations ----
help=$(t_expr --defs "$defs" marble --help)
grep -q -- '--veins X .*sine periods.*\[0\.\.100\] (default 3)' <<<"$help" &&
    ok "--help lists a composed primitive's parameters with range and default" ||
    notok "--help lists parameters" "$(grep -- --veins <<<"$help")"
t_expr --defs "$defs" marble --veins 1 --strength 0 -s 64 -o "$T/v1.exr"
t_expr '0.5 + 0.5*sin(2*pi*u)' -s 64 -o "$T/sine.exr"
same "marble with strength 0 is the plain sine" "$T/v1.exr" "$T/sine.exr" 1e-6
check_fails "a parameter out of its declared range is refused" 2 \
    t_expr --defs "$defs" marble --veins 200 -o "$T/bad.exr"
grep -q "veins must be 0..100" "$T/.err" && ok "the message gives the range" ||
    notok "range message" "$(cat "$T/.err")"
[ ! -e "$T/bad.exr" ] && ok "no output left by a refused parameter" || notok "output left"
check_fails "a non-whole octaves reaches the callee's row" 2 \
    t_expr --defs "$defs" marble --octaves 2.5 -o "$T/bad.exr"
grep -q "primitives.tp:[0-9]*:[0-9]*: octaves" "$T/.err" && ok "and names the call's position" ||
    notok "callee row message" "$(cat "$T/.err")"

# ---- tiling and solids ----
t_expr 'turbulence(frequency = 4) + 0.5*noise(frequency = 8)' --tile -s 64 -o "$T/tile.exr"
t_turbulence -f 4 --tile -s 64 -o "$T/tt.exr"
t_noise -f 8 --tile -s 64 -o "$T/tn.exr"
t_op mul "$T/tn.exr" 0.5 | t_op add "$T/tt.exr" - >"$T/tsum.exr"
same "--tile passes to the parts: the sum of tiled parts" "$T/tile.exr" "$T/tsum.exr" 1e-6
check_fails "--tile is refused when a part cannot tile" 2 t_expr 'wood()' --tile -o "$T/bad.exr"
check_fails "three coordinates to a 2D-only primitive" 2 t_expr 'polygon(u, v, w)' -o "$T/bad.exr"

# ---- errors carry the position ----
err() { # err NAME EXPR PATTERN
    if t_expr "$2" -s 8 -o "$T/bad.exr" 2>"$T/e" </dev/null; then
        notok "$1" "accepted"
    elif [ $? = 2 ] && grep -q "$3" "$T/e" && [ "$(wc -l <"$T/e")" = 1 ] && [ ! -e "$T/bad.exr" ]; then
        ok "$1"
    else
        notok "$1" "$(cat "$T/e")"
    fi
}
err "unknown name, with its column" '0.5 + foo' "EXPR:1:7: unknown name 'foo'"
err "unknown primitive" '1 + nosuch(octaves = 3)' "EXPR:1:5: unknown primitive or function 'nosuch'"
err "a function's arity" 'sin(u, v)' "EXPR:1:1: sin takes 1 argument"
err "a parameter the callee lacks" 'noise(octavs = 3)' "EXPR:1:7: noise has no parameter 'octavs'"
err "a callee's range, at the argument" 'turbulence(octaves = 99)' "EXPR:1:12: octaves must be 1..30"
err "a grid primitive has no value at a point" 'spectral()' "EXPR:1:1: spectral is made on a whole grid"
err "a colour is not a number" 'rgb(1, 0, 0)' "EXPR:1:1: a colour"
err "an argument that depends on the point" 'noise(frequency = 8*u)' "EXPR:1:19: the value of frequency must not depend"
long=$(python3 -c 'print("+".join(["u"] * 10002))')
err "an expression too long" "$long" "expression too long (more than 10000 operators)"
deep=$(python3 -c 'print("noise(" * 10 + ")" * 10)')
err "calls nested too deeply" "$deep" "calls nested too deeply"
cat >"$T/rec.tp" <<'D'
primitive a(k = 1 in 0 to 2) = k*noise()
primitive b = a(k = 2) + b()
D
check_fails "a definition through itself is refused" 2 t_expr --defs "$T/rec.tp" b -o "$T/bad.exr"
grep -q "rec.tp:2:26: recursive definition: 'b' calls itself" "$T/.err" && ok "recursion names the call" ||
    notok "recursion message" "$(cat "$T/.err")"
cat >"$T/fwd.tp" <<'D'
primitive c = d()
primitive d = noise()
D
check_fails "a primitive used before its definition" 2 t_expr --defs "$T/fwd.tp" d -o "$T/bad.exr"
grep -q "fwd.tp:1:15: unknown primitive or function 'd'" "$T/.err" && ok "and named at its use" ||
    notok "forward message" "$(cat "$T/.err")"
printf 'primitive noise = u\n' >"$T/dup.tp"
check_fails "a definition may not hide a primitive" 2 t_expr --defs "$T/dup.tp" u -o "$T/bad.exr"
printf 'primitive m(x = 5 in 0 to 1) = x\n' >"$T/range.tp"
check_fails "a default outside its range" 2 t_expr --defs "$T/range.tp" m -o "$T/bad.exr"
check_fails "a missing definitions file" 1 t_expr --defs "$T/none.tp" u -o "$T/bad.exr"

# ---- scenes: inline definitions, solid textures ----
cat >"$T/s.scene" <<'S'
image 48 48
camera { eye 0 0 -3 look 0 0 0 fov 40 }
light point { position -3 4 -5 intensity 1 }
primitive veined(k = 4 in 0 to 20) = 0.5 + 0.5*sin(k*u + 6*turbulence(octaves = 4))
texture m veined { solid k 6 seed 2 }
surface s { Kd 0.9 apply m { mapping solid Kd = f } }
sphere { centre 0 0 0 radius 1 surface s }
S
check "a scene defines a primitive and uses it as a solid texture" t_apply "$T/s.scene" -q -o "$T/s.exr"
sd=$(info_json "$T/s.exr" stats 0 stddev)
approx "$sd" 0 0.01 && notok "the solid texture shows" "stddev $sd" || ok "the solid texture shows"
sed 's/solid k 6/solid k 60/' "$T/s.scene" >"$T/s2.scene"
check_fails "a scene's value out of the declared range" 2 t_apply "$T/s2.scene" -q -o "$T/bad.exr"
grep -q "k must be 0..20" "$T/.err" && ok "with the range" || notok "scene range" "$(cat "$T/.err")"
printf 'primitives "%s"\ntexture r rings { solid }\n' "$defs" >"$T/p.scene"
sed -n '1,3p;6,7p' "$T/s.scene" | sed 's/apply m/apply r/' >>"$T/p.scene"
check "a scene reads a definitions file (primitives \"FILE\")" t_apply "$T/p.scene" -q -o "$T/p.exr"

# ---- composition scripts ----
cat >"$T/c.tc" <<S
tessellation t; size 128 by 64; cell 64 by 64;
primitives "$defs";
primitive ring2 = rings(rings = 2);
images a = marble(veins = 2); b = ring2(); end images;
built with (1,1) a; (2,1) b; end tessellation;
S
check "a script defines and reads composed primitives" t_compose "$T/c.tc" -o "$T/c.exr"
printf 'tessellation t; size 64 by 64;\nprimitives "%s";\nimages a = marble(veins = 2); end images;\nbuilt with (1,1) a; end tessellation;\n' \
    "$defs" >"$T/c1.tc"
t_compose "$T/c1.tc" -o "$T/c1.exr"
t_expr --defs "$defs" marble --veins 2 -s 64 -S 0 -o "$T/m2.exr"
same "a script's marble is t_expr's (seed 0 in scripts)" "$T/c1.exr" "$T/m2.exr" 0
printf 'tessellation t; size 8 by 8;\nprimitive z = nope();\nimages a = z(); end images;\nbuilt with (1,1) a; end tessellation;\n' >"$T/bad.tc"
check_fails "a script's definition error" 2 t_compose "$T/bad.tc" -o "$T/bad.exr"
grep -q "bad.tc:2:15: unknown primitive or function 'nope'" "$T/.err" && ok "names the script's line and column" ||
    notok "script position" "$(cat "$T/.err")"
