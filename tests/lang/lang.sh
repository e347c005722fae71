#!/usr/bin/env bash
# The one lexer and expression grammar (lang/lex.h, lang/expr.h) in both languages:
# scenes (t_apply) and composition scripts (t_compose).  Same limits, names,
# functions and file:line:col messages.
. "$(dirname "$0")/../lib.sh"

# chain N TERM OP: "TERM OP TERM OP ... TERM", N terms
chain() { python3 -c 'import sys; print((" %s " % sys.argv[3]).join([sys.argv[2]] * int(sys.argv[1])))' "$@"; }
scene() { printf 'texture t noise { }\nsurface s { apply t { Kd = %s } }\nsphere { surface s }\n' "$1" >"$T/$2.scene"; }
script() { printf 'tessellation t; size 8 by 8;\nbuilt with (1,1) %s; end tessellation;\n' "$1" >"$T/$2.tc"; }
# says NAME PATTERN: the last failure's one line matches PATTERN
says() { if grep -Eq -- "$2" "$T/.err"; then ok "$1 says '$2'"; else notok "$1 message" "$(cat "$T/.err")"; fi; }

# 1. Long chains: refused with one line naming file:line:col, never a crash.
for op in + '*'; do
    for term in f 0; do
        scene "$(chain 100000 "$term" "$op")" long
        check_fails "scene: 100000-term chain '$term $op ...'" 2 t_apply -s 8x6 -o "$T/l.png" "$T/long.scene"
        says "scene: 100000-term chain '$term $op ...'" 'long\.scene:2:[0-9]+: expression too long \(more than 10000 operators\)'
    done
    for term in 'noise()' 0; do
        script "$(chain 100000 "$term" "$op")" long
        check_fails "script: 100000-term chain '$term $op ...'" 2 t_compose -o "$T/l.exr" "$T/long.tc"
        says "script: 100000-term chain '$term $op ...'" 'long\.tc:2:[0-9]+: expression too long \(more than 10000 operators\)'
    done
done
# Chains under the limit are evaluated, without recursion along them.
scene "$(chain 9000 f +) - 8999 * f" sum
check "scene: a 9000-term sum renders" t_apply -s 8x6 --spp 1 -o "$T/sum.png" "$T/sum.scene"
scene "$(chain 9000 f '*')" prod
check "scene: a 9000-term product renders (no polynomial: the stack machine)" \
    t_apply -s 8x6 --spp 1 -o "$T/prod.png" "$T/prod.scene"
script "$(chain 2000 'noise()' '*')" prod
check "script: a 2000-term product composes" t_compose -o "$T/prod.exr" "$T/prod.tc"
# Nesting: 100 levels are read, 101 are not (both languages; an operand alone is one level).
open=$(printf '(%.0s' $(seq 99)) close=$(printf ')%.0s' $(seq 99))
scene "${open}f${close}" deep
check "scene: 100 levels of nesting" t_apply -s 8x6 --spp 1 -o "$T/deep.png" "$T/deep.scene"
script "${open}noise()${close}" deep
check "script: 100 levels of nesting" t_compose -o "$T/deep.exr" "$T/deep.tc"
scene "(${open}f${close})" deeper
check_fails "scene: 101 levels of nesting" 2 t_apply -s 8x6 -o "$T/d.png" "$T/deeper.scene"
says "scene: 101 levels" 'deeper\.scene:2:[0-9]+: expression nested too deeply \(more than 100 levels\)'
script "(${open}noise()${close})" deeper
check_fails "script: 101 levels of nesting" 2 t_compose -o "$T/d.exr" "$T/deeper.tc"
says "script: 101 levels" 'deeper\.tc:2:[0-9]+: expression nested too deeply \(more than 100 levels\)'

# 2. Names: a hyphen before a letter belongs to the name, in both languages.
printf 'tessellation t; size 32 by 32;\nbuilt with (1,1) bubble(size-spread = 0.5); end tessellation;\n' >"$T/hy.tc"
check "script: bubble(size-spread = 0.5)" t_compose -o "$T/hy.exr" "$T/hy.tc"
printf 'tessellation t; size 32 by 32;\nbuilt with (1,1) bubble(); end tessellation;\n' >"$T/hy0.tc"
t_compose -o "$T/hy0.exr" "$T/hy0.tc"
t_op sub "$T/hy.exr" "$T/hy0.exr" | t_op abs - | t_info --json >"$T/hy.json"
python3 -c 'import json,sys; sys.exit(max(c["max"] for c in json.load(open(sys.argv[1]))["stats"][:1]) < 1e-3)' \
    "$T/hy.json" && ok "script: size-spread = 0.5 reaches the primitive" ||
    notok "script: size-spread reached the primitive"
printf 'texture t bubble { size-spread 0.5 }\nsurface s { apply t { Kd = f } }\nsphere { surface s }\n' >"$T/hy.scene"
check "scene: bubble { size-spread 0.5 }" t_apply -s 8x6 --spp 1 -o "$T/hy.png" "$T/hy.scene"
script 'bubble(size-sprd = 0.5)' hyb
check_fails "script: an unknown hyphenated parameter" 2 t_compose -o "$T/x.exr" "$T/hyb.tc"
says "script: unknown hyphenated parameter" 'hyb\.tc:2:25: .*size-sprd'
printf 'texture t bubble { size-sprd 0.5 }\n' >"$T/hyb.scene"
check_fails "scene: an unknown hyphenated parameter" 2 t_apply -o "$T/x.png" "$T/hyb.scene"
says "scene: unknown hyphenated parameter" 'hyb\.scene:1:[0-9]+: .*size-sprd'

# 3. The shared functions work in both languages, with the same messages.
t_noise -s 8 -S 1 -o "$T/n1.exr"
t_noise -s 8 -S 2 -o "$T/n2.exr"
script "max(\"$T/n1.exr\", \"$T/n2.exr\")" fmax
script "\"$T/n1.exr\" max \"$T/n2.exr\"" omax
t_compose -o "$T/fmax.exr" "$T/fmax.tc" && t_compose -o "$T/omax.exr" "$T/omax.tc"
same "script: max(a, b) is a max b" "$T/fmax.exr" "$T/omax.exr"
script "abs(\"$T/n1.exr\" - 0.5) + min(0.2, \"$T/n2.exr\")" fns
check "script: abs and min" t_compose -o "$T/fns.exr" "$T/fns.tc"
scene 'max(f, 0.5) - abs(-0.2) + min(p, rgb(0.1, 0.2, 0.3))' fns
check "scene: max, abs, min, rgb" t_apply -s 8x6 --spp 1 -o "$T/fns.png" "$T/fns.scene"
scene 'min(f)' bad
check_fails "scene: min with one argument" 2 t_apply -o "$T/x.png" "$T/bad.scene"
says "scene: min with one argument" 'bad\.scene:2:28: min takes 2 arguments$'
script 'min("a.exr")' bad
check_fails "script: min with one argument" 2 t_compose -o "$T/x.exr" "$T/bad.tc"
says "script: min with one argument" 'bad\.tc:2:18: min takes 2 arguments$'

# 4. One lexer: the same number and string rules, the same messages.
scene 'f + 3x' bad
check_fails "scene: a number running into a letter" 2 t_apply -o "$T/x.png" "$T/bad.scene"
says "scene: malformed number" "bad\.scene:2:32: malformed number '3x'"
script 'noise() + 3x' bad
check_fails "script: a number running into a letter" 2 t_compose -o "$T/x.exr" "$T/bad.tc"
says "script: malformed number" "bad\.tc:2:28: malformed number '3x'"
scene 'f + @' bad
check_fails "scene: a stray character" 2 t_apply -o "$T/x.png" "$T/bad.scene"
says "scene: stray character" "bad\.scene:2:32: unexpected character '@'"
script 'noise() + @' bad
check_fails "script: a stray character" 2 t_compose -o "$T/x.exr" "$T/bad.tc"
says "script: stray character" "bad\.tc:2:28: unexpected character '@'"
# "f -1" is "f - 1" in both: a signed number after an operand is the operator
scene 'f -0.25' sg1
scene 'f - 0.25' sg2
t_apply -s 16x12 --spp 1 -o "$T/sg1.exr" "$T/sg1.scene" && t_apply -s 16x12 --spp 1 -o "$T/sg2.exr" "$T/sg2.scene"
same "scene: 'f -0.25' is 'f - 0.25'" "$T/sg1.exr" "$T/sg2.exr"
