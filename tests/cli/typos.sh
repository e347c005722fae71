#!/usr/bin/env bash
# A mistyped name gets the nearest as getopt-style tools give it: every long option of every
# tool, every palette, every primitive, every choice of an option and every word of a scene
# block, each with two neighbouring letters swapped, is refused with one line naming the
# name meant.
. "$(dirname "$0")/../lib.sh"

# typo WORD: WORD with the two letters after its middle swapped ("frequency" -> "freuqency")
typo() { awk -v w="$1" 'BEGIN { m = int(length(w) / 2); print substr(w, 1, m) substr(w, m + 2, 1) substr(w, m + 1, 1) substr(w, m + 3) }'; }

# 1. Options: every long option of 5 letters or more, each name once (on the first tool that
# has it: the shared options are the same rows everywhere).
bad= n=0 seen=" "
for bin in "$TEXTURA_BUILD"/bin/t_*; do
    tool=$(basename "$bin")
    for opt in $("$bin" --help | sed -En 's/^  (-[A-Za-z0-9],|   ) --([a-z0-9-]+).*/\2/p'); do
        [ ${#opt} -ge 5 ] && [ "${seen/ $opt /}" = "$seen" ] || continue
        seen="$seen$opt "
        t=$(typo "$opt")
        [ "$t" = "$opt" ] && continue
        msg=$("$bin" "--$t" 2>&1 >/dev/null </dev/null)
        n=$((n + 1))
        grep -q -- "did you mean --$opt?" <<<"$msg" || bad="$bad; $tool --$t: $msg"
    done
done
[ -z "$bad" ] && ok "$n mistyped options each name the option meant" || notok "mistyped options" "${bad:2:600}"

# 2. Palettes, primitives and choices.
bad= n=0
for p in $(t_palette --list | awk '{ print $1 }'); do
    [ ${#p} -ge 4 ] || continue
    msg=$(t_palette "$(typo "$p")" </dev/null 2>&1 >/dev/null)
    n=$((n + 1))
    grep -q "did you mean $p?" <<<"$msg" || bad="$bad; palette $p: $msg"
done
# the registry, as the message for a name near nothing lists it
printf 'texture t zzzzzzzz { }\n' >"$T/p.scene"
prims=$(t_apply -o "$T/x.png" "$T/p.scene" 2>&1 | sed -n 's/.*(known: \(.*\))$/\1/p' | tr -d ,)
[ "$(wc -w <<<"$prims")" -ge 25 ] || bad="$bad; the registry: $prims"
for p in $prims; do
    [ ${#p} -ge 4 ] || continue
    printf 'texture t %s { }\n' "$(typo "$p")" >"$T/p.scene"
    msg=$(t_apply -o "$T/x.png" "$T/p.scene" 2>&1 >/dev/null)
    n=$((n + 1))
    grep -q "did you mean $p?" <<<"$msg" || bad="$bad; primitive $p: $msg"
done
for c in fbm:ridged:t_fractal:--mode plain:twill:t_weave:--weave clamp:mirror:t_filter:--edge; do
    IFS=: read -r _ choice bin opt <<<"$c"
    args=(); [ "$bin" = t_filter ] && args=(blur "$T/none.exr")
    msg=$("$bin" "$opt" "$(typo "$choice")" "${args[@]}" 2>&1 >/dev/null </dev/null)
    n=$((n + 1))
    grep -q "did you mean $choice?" <<<"$msg" || bad="$bad; $bin $opt: $msg"
done
msg=$(t_op "$(typo threshold)" 0 1 2>&1 >/dev/null)
grep -q "did you mean threshold?" <<<"$msg" || bad="$bad; t_op: $msg"
msg=$(t_filter "$(typo emboss)" "$T/none.exr" 2>&1 >/dev/null)
grep -q "did you mean emboss?" <<<"$msg" || bad="$bad; t_filter: $msg"
[ -z "$bad" ] && ok "$n mistyped palettes, primitives and choices each name the one meant" ||
    notok "mistyped palettes, primitives and choices" "${bad:2:600}"

# 3. Scene words: every word of the settings and the camera, light and surface blocks.
bad= n=0
for block in settings camera light surface; do
    for w in $(t_apply --help-scene "$block" | awk '{ print $1 }' | grep -E '^[a-z][a-z-]{3,}$'); do
        case $block in
        settings) printf '%s 1\n' "$(typo "$w")" ;;
        camera) printf 'camera { %s 1 }\n' "$(typo "$w")" ;;
        light) printf 'light point { %s 1 }\n' "$(typo "$w")" ;;
        surface) printf 'surface s { %s 1 }\n' "$(typo "$w")" ;;
        esac >"$T/w.scene"
        msg=$(t_apply -o "$T/x.png" "$T/w.scene" 2>&1 >/dev/null)
        n=$((n + 1))
        grep -q "did you mean $w?" <<<"$msg" || bad="$bad; $block $w: $msg"
    done
done
[ "$n" -gt 20 ] && [ -z "$bad" ] && ok "$n mistyped scene words each name the word meant" ||
    notok "mistyped scene words ($n)" "${bad:2:600}"
# A word far from every name gets no guess.
msg=$(t_noise --zzzzzzzz 2>&1 >/dev/null)
grep -q "did you mean" <<<"$msg" && notok "no guess for a word near nothing" "$msg" || ok "no guess for a word near nothing"
check_fails "a mistyped option is one line, exit 2" 2 t_noise --frequnecy 3
