#!/bin/bash
# t_apply: the torus's bad parameters (file:line:column, exit 2, no output file)
. tests/lib.sh

bad() {
    local name=$1 text=$2
    printf '%s\n' "$text" >"$T/bad.scene"
    check_fails "$name" 2 t_apply "$T/bad.scene" -o "$T/bad.png"
    if [ -e "$T/bad.png" ]; then notok "$name: no output file"; rm -f "$T/bad.png"; fi
    grep -q "bad.scene:[0-9]*:[0-9]*:" "$T/.err" || notok "$name: message names file:line:column" "$(cat "$T/.err")"
}
bad "torus minor radius 0" 'torus { major 1 minor 0 }'
bad "torus minor radius < 0" 'torus { major 1 minor -0.5 }'
bad "torus major radius < 0" 'torus { major -1 minor 0.5 }'
bad "torus NaN radius" 'torus { major nan minor 0.5 }'
bad "torus zero axis" 'torus { axis 0 0 0 }'
bad "torus unknown word" 'torus { radius 1 }'
printf 'image 8 8\n\n  torus { major 1 minor -1 }\n' >"$T/at.scene"
t_apply "$T/at.scene" -o "$T/at.png" 2>"$T/at.err"
grep -q "at.scene:3:3: torus minor radius must be > 0" "$T/at.err" &&
    ok "torus error names line 3 column 3" || notok "torus error place" "$(cat "$T/at.err")"
check "torus { } renders with its defaults" t_apply /dev/stdin -s 16x12 -o "$T/d.exr" \
    <<<'camera { eye 0 3 -4 look 0 0 0 } torus { }'
