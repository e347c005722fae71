#!/usr/bin/env bash
# One command line across the tools (textura(5), "Option names"): every flag
# means one thing, old names warn, options of another mode are refused,
# lists, grey colours, and the bytes of a map do not depend on -j.
. "$(dirname "$0")/../lib.sh"
B=${TEXTURA_BUILD:-build}/bin
page=${TEXTURA_TOP:-.}/man/man5/textura.5
unset TEXTURA_DEPRECATED

# Every name of every tool, from its rows: FLAG ROW HOW TYPE META RANGE, with the tool.
for t in "$B"/t_*; do
    "$t" --help-options | sed "s|^|$(basename "$t")\t|"
done >"$T/names"
[ "$(cut -f1 "$T/names" | sort -u | wc -l)" -eq "$(ls "$B"/t_* | wc -l)" ] &&
    ok "every tool lists its names (--help-options)" || notok "every tool lists its names"

# The documented vocabulary and exceptions of textura(5).
section() { sed -n "/^\.\\\\\" begin $1/,/^\.\\\\\" end $1/p" "$page"; }
section vocabulary | sed -n 's/^\.It Fl //p' | tr -d ',' | tr ' ' '\n' | sed -n 's/^-/--/p' |
    sort -u >"$T/vocabulary"
section exceptions | sed -n 's/^\.It Fl //p' | tr -d ',' | tr ' ' '\n' | sed -n 's/^-/--/p' |
    sort -u >"$T/exceptions"
[ -s "$T/vocabulary" ] && [ -s "$T/exceptions" ] &&
    ok "textura(5) has the vocabulary and the exceptions" || notok "textura(5) sections"

# 1. No name is taken by two rows of one tool.
clash=$(awk -F'\t' '$4 == "clash"' "$T/names")
[ -z "$clash" ] && ok "no tool has two options of one name" || notok "clashes" "$clash"

# 2. A short flag stands for the same long option in every tool.
bad=$(awk -F'\t' '$4 == "short" { if ($2 in row && row[$2] != $3) print $2 ": " row[$2] " and " $3 " (" $1 ")"; row[$2] = $3 }' "$T/names")
[ -z "$bad" ] && ok "each short flag means one thing across the tools" ||
    notok "short flags of two meanings" "$bad"

# 3. A long name (or alias) stands for one row and one type everywhere, but for
#    the exceptions; and one used by several tools is in the vocabulary.
bad=$(awk -F'\t' -v ex="$T/exceptions" '
    BEGIN { while ((getline e < ex) > 0) except[e] = 1 }
    $4 == "name" || $4 == "alias" {
        k = $2
        if (k in except || $3 in except) next
        if (k in row && (row[k] != $3 || type[k] != $5))
            print k ": " row[k] "/" type[k] " in " tool[k] ", " $3 "/" $5 " in " $1
        row[k] = $3; type[k] = $5; tool[k] = $1
    }' "$T/names" | sort -u)
[ -z "$bad" ] && ok "each long name means one thing across the tools" ||
    notok "long names of two meanings" "$(head -5 <<<"$bad")"
awk -F'\t' '$4 == "name" { n[$2]++ } END { for (k in n) if (n[k] > 1) print k }' "$T/names" |
    sort >"$T/shared"
missing=$(comm -23 "$T/shared" "$T/vocabulary")
[ -z "$missing" ] && ok "every long name shared by tools is in textura(5)'s vocabulary" ||
    notok "shared names missing from textura(5)" "$missing"
stale=$(comm -13 "$T/shared" "$T/vocabulary")
[ -z "$stale" ] && ok "textura(5)'s vocabulary names no option that is not shared" ||
    notok "vocabulary lists names no two tools share" "$stale"

# 4. No long option of one letter, except as an alias.
bad=$(awk -F'\t' '$4 == "name" && length($2) == 3' "$T/names")
[ -z "$bad" ] && ok "no long option is a single letter" || notok "single-letter names" "$bad"
awk -F'\t' '$4 == "alias" && length($2) == 3' "$T/names" | grep -q . &&
    ok "the thesis's letters stay as aliases (--h, --c, --z)" || notok "no letter aliases"

# 5. Both spellings; the manuals write the UK one.
bad=$(awk -F'\t' '$4 == "name" && $2 ~ /colou?r|cent(er|re)|gr[ae]y|quanti[sz]e/ { print $1, $2 }' "$T/names" |
    while read -r t n; do
        us=$(sed 's/colour/color/; s/centre/center/; s/grey/gray/; s/quantise/quantize/' <<<"$n")
        [ "$us" = "$n" ] || grep -qP "^$t\t$us\t$n\tspelling" "$T/names" || echo "$t $n"
        grep -qE 'color|center|gray|quantize' <<<"$n" && echo "$t $n (US spelling)"
    done)
[ -z "$bad" ] && ok "every UK-spelt name also takes its US spelling" || notok "spellings" "$bad"
"$B/t_ring" -s 16 --colour1 '#204060' -o "$T/uk.pfm" && "$B/t_ring" -s 16 --color1 '#204060' -o "$T/us.pfm" 2>"$T/err"
same "--color1 is --colour1" "$T/uk.pfm" "$T/us.pfm"
[ ! -s "$T/err" ] && ok "a US spelling takes no warning" || notok "US spelling warned" "$(cat "$T/err")"

# 6. Old names work with one warning, hidden from --help, listed in textura(5).
"$B/t_ring" -s 16 --ring-width 0.2 -o "$T/new.pfm"
"$B/t_ring" -s 16 -d 0.2 -o "$T/old.pfm" 2>"$T/err"
same "t_ring -d is --ring-width" "$T/new.pfm" "$T/old.pfm"
[ "$(cat "$T/err")" = "t_ring: warning: -d is deprecated and will be removed: write --ring-width" ] &&
    ok "an old name warns in one line naming the new one" || notok "deprecation warning" "$(cat "$T/err")"
"$B/t_ring" -q -s 16 --width 0.2 -o "$T/old2.pfm" 2>"$T/err"
[ ! -s "$T/err" ] && ok "-q silences the warning" || notok "-q and the warning" "$(cat "$T/err")"
same "t_ring --width is --ring-width" "$T/new.pfm" "$T/old2.pfm"
"$B/t_bubble" -s 32 -n 30 -o "$T/b1.pfm" 2>/dev/null && "$B/t_bubble" -s 32 -c 30 -o "$T/b2.pfm"
same "t_bubble -n is -c" "$T/b1.pfm" "$T/b2.pfm"
check_fails "TEXTURA_DEPRECATED=error refuses an old name" 2 bash -c "TEXTURA_DEPRECATED=error $B/t_ring -d 0.2"
bad=$(awk -F'\t' '$4 == "old" { print $1 "\t" $2 }' "$T/names" | while IFS=$'\t' read -r t n; do
    "$B/$t" --help | grep -qE -- "(^|[ ,])$n( |,|$)" && echo "$t lists $n in --help"
    f=$(sed 's/^-/Fl /' <<<"$n")
    grep -qF "$t 1 Ta $f Ta" "$page" || echo "$t $n is not in textura(5)"
done)
[ -z "$bad" ] && ok "every old name is hidden from --help and listed in textura(5)" ||
    notok "old names" "$(head -5 <<<"$bad")"
printf 'image 8 8\ntexture t ring { width 0.2 }\nsurface s { apply t { Kd = f } }\nsphere { surface s }\n' >"$T/old.scene"
"$B/t_apply" "$T/old.scene" -o "$T/old.exr" 2>"$T/err"
grep -q "'width' is deprecated and will be removed: write 'ring-width'" "$T/err" &&
    ok "an old word in a scene warns" || notok "old scene word" "$(cat "$T/err")"
check_fails "an old word in a scene is refused under TEXTURA_DEPRECATED=error" 2 \
    bash -c "TEXTURA_DEPRECATED=error $B/t_apply $T/old.scene -o $T/old.exr"

# 6b. Long options are written whole.
check_fails "an abbreviated option is refused" 2 "$B/t_noise" --freq 3
grep -q "written whole (--frequency?)" "$T/.err" && ok "its message names the whole option" ||
    notok "abbreviation message" "$(cat "$T/.err")"
check "--frequency=3 is taken" "$B/t_noise" -s 8 --frequency=3 -o "$T/f3.pfm"

# 7. Options of another mode are refused, naming the mode.
says() { # NAME MESSAGE CMD...
    local name=$1 msg=$2
    shift 2
    check_fails "$name" 2 "$@"
    grep -qF -- "$msg" "$T/.err" && ok "$name: the message says so" || notok "$name: message" "$(cat "$T/.err")"
}
says "t_fractal -m fbm --c" "--c applies to --mode julia only" "$B/t_fractal" -m fbm --c 1,1
says "t_fractal -m julia -n" "-n applies to --mode fbm, ridged, hybrid only" "$B/t_fractal" -m julia -n 4
says "t_fractal --recursions outside koch" "--recursions applies to --mode koch only" "$B/t_fractal" --recursions 3
check "t_fractal -m koch --recursions 3" "$B/t_fractal" -m koch --recursions 3 -s 16 -o "$T/k.pfm"
"$B/t_noise" -s 16 -o "$T/n.pfm"
says "t_filter blur --radius" "--radius applies to the operation box, median only" "$B/t_filter" blur --radius 3 "$T/n.pfm"
check "t_filter box --radius" "$B/t_filter" box --radius 3 "$T/n.pfm" -o "$T/f.pfm"
says "t_d_noise --strength without --normal" "--strength applies with --normal only" "$B/t_d_noise" --strength 2
says "--format against -o's extension" "--format tif contradicts the extension of $T/x.png" "$B/t_noise" -o "$T/x.png" --format tif
says "t_spectral -D with --h" "give one" "$B/t_spectral" -D 2.5 --h 0.5
says "t_bubble --clusters without the cluster distribution" "--clusters applies to --distribution cluster only" "$B/t_bubble" --clusters 4
says "t_palette --stops without --from" "--stops and --space apply" "$B/t_palette" --stops 4 marble "$T/n.pfm"

# 8. Lists.
npal=$(ls "${TEXTURA_TOP:-.}"/palettes/*.pal | wc -l)
[ "$("$B/t_palette" --list | wc -l)" -eq "$npal" ] && ok "t_palette --list names the $npal palettes" ||
    notok "t_palette --list" "$("$B/t_palette" --list | head -3)"
"$B/t_palette" --list | grep -q $'\e' && notok "t_palette --list to a pipe has no colour codes" ||
    ok "t_palette --list to a pipe has no colour codes"
if command -v script >/dev/null; then
    TERM=xterm script -qc "$B/t_palette --list" /dev/null >"$T/tty" </dev/null
    grep -q $'\e\[48;2;' "$T/tty" && ok "t_palette --list on a terminal draws swatches" ||
        notok "swatches on a terminal" "$(head -c 200 "$T/tty")"
else
    skip "t_palette --list on a terminal draws swatches" "script(1) is not installed"
fi
check_fails "an unknown palette lists the known ones" 2 "$B/t_palette" nosuchpalette "$T/n.pfm"
grep -q "marble" "$T/.err" && ok "its message names them" || notok "unknown palette message" "$(cat "$T/.err")"
TEXTURA_MATERIALS=${TEXTURA_TOP:-.}/patterns/materials.txt "$B/t_apply" --list-materials >"$T/mat"
grep -q "^gold  *conductor" "$T/mat" && grep -q "dielectric" "$T/mat" &&
    ok "t_apply --list-materials" || notok "t_apply --list-materials" "$(head -3 "$T/mat")"
[ "$("$B/t_info" --primitives | wc -l)" -ge 20 ] && ok "t_info --primitives lists the primitives" ||
    notok "t_info --primitives"
check_fails "an unknown filter lists the operations" 2 "$B/t_filter" frobnicate "$T/n.pfm"
grep -q "blur|box" "$T/.err" && ok "its message names them" || notok "unknown filter message" "$(cat "$T/.err")"
printf 'image 8 8\ntexture t nosuch { }\nsurface s { apply t { Kd = f } }\nsphere { surface s }\n' >"$T/u.scene"
check_fails "an unknown primitive in a scene lists the primitives" 2 "$B/t_apply" "$T/u.scene" -o "$T/u.exr"
grep -q "known: brick, bubble" "$T/.err" && ok "its message names them" || notok "unknown primitive message" "$(cat "$T/.err")"
printf 'image 8 8\nsurface s { material nosuch }\nsphere { surface s }\n' >"$T/m.scene"
TEXTURA_MATERIALS=${TEXTURA_TOP:-.}/patterns/materials.txt check_fails "an unknown material lists the materials" 2 "$B/t_apply" "$T/m.scene" -o "$T/u.exr"
grep -q "known: gold" "$T/.err" && ok "its message names them" || notok "unknown material message" "$(cat "$T/.err")"
check_fails "an unknown mode lists the modes" 2 "$B/t_fractal" -m nosuch
grep -q "fbm|ridged" "$T/.err" && ok "its message names them" || notok "unknown mode message" "$(cat "$T/.err")"

# 9. A grey level wherever a colour goes.
"$B/t_ring" -s 16 --colour1 0.5 -o "$T/g1.pfm" && "$B/t_ring" -s 16 --colour1 0.5,0.5,0.5 -o "$T/g3.pfm"
same "--colour1 0.5 is 0.5,0.5,0.5" "$T/g1.pfm" "$T/g3.pfm"
check "t_xform --background 0.2 on a grey map" "$B/t_xform" --expand 24x24 --background 0.2 "$T/n.pfm" -o "$T/x.pfm"
[ "$(info_json "$T/x.pfm" stats 0 min)" = 0.2 ] || approx "$(info_json "$T/x.pfm" stats 0 min)" 0.2 1e-6 &&
    ok "the grey background is 0.2" || notok "grey background" "$(info_json "$T/x.pfm" stats 0 min)"

# 10. The same bytes for any -j: the history leaves -j and -q out.
for cmd in "t_noise -s 64" "t_turbulence -s 48 -n 4" "t_bubble -s 40 -c 20" "t_ring -s 32"; do
    set -- $cmd
    t=$1
    shift
    "$B/$t" "$@" -j 1 >"$T/j1.exr" && "$B/$t" "$@" -j2 -q >"$T/j2.exr"
    cmp -s "$T/j1.exr" "$T/j2.exr" && ok "$cmd: -j 1 and -j2 -q write the same bytes" ||
        notok "$cmd: bytes differ with -j"
done
"$B/t_noise" -s 8 --threads=2 -o "$T/h.exr"
"$B/t_info" "$T/h.exr" | grep -q "threads" && notok "--threads= is not in the history" ||
    ok "--threads= is not in the history"
"$B/t_noise" -s 8 -f 3 -j 2 | "$B/t_info" | grep -q "t_noise -s 8 -f 3$" &&
    ok "the history keeps the options that change the map" || notok "history"

# 11. Progress: a bar on a terminal for work past a moment, never into a pipe or with -q.
if command -v script >/dev/null; then
    "$B/t_noise" -s 512 -o "$T/n512.pfm"
    run_tty() { script -qc "$*" /dev/null </dev/null | tr '\r' '\n'; }
    run_tty "$B/t_filter median -r 8 -j 1 $T/n512.pfm -o $T/m.pfm" >"$T/tty"
    grep -q "^t_filter: \[#* *\]  *[0-9]*%" "$T/tty" && grep -q "100%" "$T/tty" &&
        ok "a long median filter draws a bar on a terminal" || notok "median progress" "$(head -c 300 "$T/tty")"
    run_tty "$B/t_filter median -q -r 8 -j 1 $T/n512.pfm -o $T/m.pfm" >"$T/tty"
    [ ! -s "$T/tty" ] && ok "-q draws no bar" || notok "-q and the bar" "$(head -c 200 "$T/tty")"
    # 6 million points: 1 s here, where 2 million took 0.3 s, the bar's own delay; half
    # of them under a sanitizer, twice as slow at this
    pts=6000000
    [ -n "$sanitized" ] && pts=3000000
    run_tty "$B/t_bubble -c $pts -s 64 -j 1 -o $T/b.pfm" >"$T/tty"
    grep -q "^t_bubble: \[" "$T/tty" && ok "a large point set draws a bar" || notok "bubble progress" "$(head -c 300 "$T/tty")"
    # quick work erases its bar: nothing is left on the screen (tests/cli/progress.sh)
    script -qc "$B/t_noise -s 32 -o $T/small.pfm" /dev/null </dev/null >"$T/tty"
    left=$(awk 'BEGIN { RS = "\r" } { last = $0 } END { gsub(/\033\[K/, "", last); printf "%s", last }' "$T/tty")
    [ -z "$left" ] && [ "$(tr -cd '\n' <"$T/tty" | wc -c)" = 0 ] && ok "quick work leaves no bar" ||
        notok "a bar left by quick work" "$(head -c 200 "$T/tty")"
else
    skip "progress bars on a terminal" "script(1) is not installed"
fi
"$B/t_filter" median -r 8 -j 1 "$T/n512.pfm" -o "$T/m2.pfm" 2>"$T/err"
[ ! -s "$T/err" ] && ok "no bar when standard error is not a terminal" || notok "bar into a file" "$(head -c 200 "$T/err")"
cmp -s "$T/m.pfm" "$T/m2.pfm" && ok "the bar does not change the map" || notok "map differs with the bar"

# 12. Every option that a --help text names exists: the tool's own, or that of
#     the tool the line names ("t_fft --as complex").
bad=$(for t in "$B"/t_*; do
    n=$(basename "$t")
    "$t" --help | grep -o -- '\(t_[a-z_0-9]* \)\?--[a-z][a-z0-9-]*' | sort -u | while read -r a b; do
        tool=$n opt=$a
        [ -n "$b" ] && tool=$a opt=$b
        case $opt in --help | --version) continue ;; esac
        awk -F'\t' -v t="$tool" -v o="$opt" '$1 == t && $2 == o && $4 != "old" { f = 1 } END { exit !f }' "$T/names" ||
            echo "$n --help names $tool $opt"
    done
done)
[ -z "$bad" ] && ok "every option named in a --help exists" || notok "--help names missing options" "$bad"
