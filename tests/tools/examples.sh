#!/usr/bin/env bash
# Every example of every manual runs: the commands of each EXAMPLES section
# (".Dl $ ..." lines, and "$ ..." lines of literal blocks) run in order in a
# folder of their own that holds the input files they name; where a literal
# block shows a command's output, the output must be the same.
. "$(dirname "$0")/../lib.sh"
B=$(cd "${TEXTURA_BUILD:-build}/bin" && pwd)
top=$(cd "${TEXTURA_TOP:-.}" && pwd)
export PATH="$B:$PATH"

# The inputs the examples name, made once; the samples t_synth reads (photo.png, and
# hole.png, its mask) at 128x128, as its pages' own sample is.
F=$T/fixtures
mkdir -p "$F/patterns"
(
    cd "$F" || exit 1
    t_noise -o map.exr && t_convert map.exr -o map.png && cp map.exr in.exr &&
        t_circle -o circle.exr && t_flower -o flower.exr && t_stripe -o stripes.exr &&
        t_noise -S 3 | t_palette marble -o marble.exr &&
        t_wood | t_palette wood -o wood.exr && t_circle --ids | t_op sub - 1 -o mask.exr &&
        t_brick -s 512 -o wall.exr && t_checker -o checker.exr && cp marble.exr leo.exr &&
        t_noise -s 128 | t_palette granite -o photo.png && t_convert map.exr -o painted.png &&
        t_circle -s 128 -r 0.1 --colour1 0 --colour2 1 -o hole.png &&
        t_convert --compression zip map.exr -o tiled.exr &&
        printf '0.25 0.25\n0.75 0.5\n0.5 0.8\n' >stars.txt &&
        cp "$top/patterns/tessellation.tc" "$top/patterns/thesis_tessellation.tc" patterns/ &&
        # the script t_compose(5) shows, as its example runs it
        awk '/^\.Bd -literal/ { b = "" ; next } /^\.Ed/ { if (b ~ /^tessellation marble;/) s = b; next }
             { b = b $0 "\n" } END { printf "%s", s }' "$top/man/man5/t_compose.5" >marble.tc &&
        [ -s marble.tc ]
) || { notok "example fixtures"; exit 0; }

# Each page's examples as a script: COMMAND lines (marked "$ ") and output lines.
examples() {
    awk '
        /^\.Sh EXAMPLES/ { e = 1; next }
        /^\.Sh / { e = 0 }
        !e { next }
        /^\.Bd -literal/ { lit = 1; seen = 0; next }
        /^\.Ed/ { lit = 0; next }
        /^\.Dl \$ / { sub(/^\.Dl \$ /, ""); print "$ " $0; next }
        lit && /^\$ / { print; seen = 1; cont = /\\e$/; next }
        lit && cont { print "+ " $0; cont = /\\e$/; next }
        lit && seen { print "= " $0 }
    ' "$1" | sed 's/\\e/\\/g; s/\\-/-/g; s/\\(aq/'"'"'/g; s/\\&//g'
}

npages=0
for page in "$top"/man/man1/*.1 "$top"/man/man5/*.5; do
    examples "$page" >"$T/ex" || continue
    [ -s "$T/ex" ] || continue
    npages=$((npages + 1))
    name=$(basename "$page")
    d=$T/run-$name
    cp -r "$F" "$d"
    cmd="" want="" bad=""
    flush() {
        [ -n "$cmd" ] || return
        got=$(cd "$d" && bash -o pipefail -c "$cmd" 2>"$T/err" </dev/null) ||
            { bad="$bad; '$cmd' failed: $(head -c 200 "$T/err")"; cmd="" want=""; return; }
        if [ -n "$want" ] && [ "$got" != "${want%$'\n'}" ]; then
            bad="$bad; '$cmd' printed: $(head -c 300 <<<"$got")"
        fi
        cmd="" want=""
    }
    while IFS= read -r line; do
        case $line in
        '$ '*) flush; cmd=${line#\$ } ;;
        '+ '*) cmd="${cmd%\\}${line#+ }" ;;
        '= '*) want="$want${line#= }"$'\n' ;;
        esac
    done <"$T/ex"
    flush
    [ -z "$bad" ] && ok "$name: its examples run" || notok "$name: examples" "${bad#; }"
done
# what an example shows, not only that it runs: t_cascade(1)'s flower fills the circle
d=$T/run-t_cascade.1
[ -s "$d/cf.exr" ] && t_xform --clip 100,100,156,156 "$d/cf.exr" -o "$T/cf_in.exr" &&
    t_xform --clip 100,100,156,156 "$F/flower.exr" -o "$T/fl_in.exr" &&
    same "t_cascade(1): the flower fills the circle's inside" "$T/cf_in.exr" "$T/fl_in.exr" ||
    notok "t_cascade(1)'s example"
[ "$npages" -ge 40 ] && ok "$npages manuals have examples" || notok "few manuals with examples: $npages"
