#!/usr/bin/env bash
# The gallery (make gallery, patterns/gallery.sh): its page shows every tool, primitive,
# fractal mode, palette, filter and operator; every picture differs from the inputs shown
# beside it; and in headless chromium every picture loads, no caption overflows its
# figure or breaks inside a word, and each thumbnail differs from its inputs by pixels.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
g=$T/gal
if ! "$top/patterns/gallery.sh" -o "$g" -s 48 >"$T/gout" 2>&1; then
    notok "gallery.sh runs" "$(head -c 300 "$T/gout")"
    exit 0
fi
grep -q "failed" "$T/gout" && notok "every picture of the gallery is made" "$(grep -m3 failed "$T/gout")" ||
    ok "gallery.sh runs, every picture made"
missing=$(sed 's/<img/\n<img/g' "$g/index.html" | sed -n 's/^<img[^>]* src="\([^"]*\)".*/\1/p' |
    sort -u | while read -r f; do [ -s "$g/$f" ] || echo "$f"; done)
n=$(grep -o '<img class="pic"' "$g/index.html" | wc -l)
[ "$n" -gt 100 ] && [ -z "$missing" ] && ok "the page shows $n pictures, every file present" ||
    notok "gallery links" "$n pictures, missing: $missing"
# the registries, enumerated: each in a caption
captions=$(cut -f3 "$g/list")
lacks=""
for p in $(t_info --primitives | awk '{ print $1 }'); do
    grep -q "t_$p " <<<"$captions" || lacks="$lacks t_$p"
done
for m in $(t_fractal --help | sed -n 's/.*--mode NAME .*\[\([a-z|]*\)\].*/\1/p' | tr '|' ' '); do
    grep -q "t_fractal .*-m $m" <<<"$captions" || lacks="$lacks fractal:$m"
done
for f in "$top"/palettes/*.pal; do
    p=$(basename "$f" .pal)
    grep -q "t_palette $p " <<<"$captions" || lacks="$lacks palette:$p"
done
for op in $(t_filter --help | sed -n '/one of:/,/^$/p' | awk 'NR > 1 && NF { print $1 }'); do
    grep -q "t_filter $op " <<<"$captions" || lacks="$lacks filter:$op"
done
for op in $(t_op '?' 2>&1 | sed -n 's/.*(valid: \(.*\))$/\1/p' | tr '|' ' '); do
    grep -q "t_op $op " <<<"$captions" || lacks="$lacks op:$op"
done
for p in $(sed -n 's/^primitive \([a-z_]*\)(.*/\1/p' "$top/patterns/primitives.tp"); do
    grep -q "t_expr --defs primitives.tp $p " <<<"$captions" || lacks="$lacks composed:$p"
done
# every tool that makes a picture (t_info reports, t_proto edits, t_convert and t_assemble
# give back the picture they read)
for b in "${TEXTURA_BUILD:-build}"/bin/t_*; do
    t=$(basename "$b")
    case $t in t_info | t_proto | t_convert | t_assemble) continue ;; esac
    grep -q "\(^\|| \)$t " <<<"$captions" || lacks="$lacks $t"
done
[ -z "$lacks" ] && ok "the gallery shows every tool, primitive, fractal mode, palette, filter, operator and composed primitive" ||
    notok "the gallery lacks" "$lacks"
# each picture differs from every input shown beside it
same_as=""
while IFS=$'\t' read -r f sec cmd ins; do
    case $cmd in "t_palette greys "*) continue ;; esac # the identity palette
    for i in $ins; do
        d=$(t_op sub "$g/$f" "$g/$i.png" --resize scale 2>/dev/null | t_op abs - | t_info --json |
            python3 -c 'import json,sys; print(max(c["mean"] for c in json.load(sys.stdin)["stats"][:3]))')
        awk -v d="${d:-0}" 'BEGIN { exit !(d > 0.01) }' || same_as="$same_as $f~$i($d)"
    done
done <"$g/list"
[ -z "$same_as" ] && ok "every picture differs from its inputs (mean difference over 0.01)" ||
    notok "pictures that look like their inputs" "$same_as"
if command -v montage >/dev/null; then
    [ -s "$g/gallery.png" ] && ok "the contact sheet is written" || notok "contact sheet"
else
    skip "the contact sheet is written" "ImageMagick's montage is not installed"
fi
# the README's pictures, 640 pixels wide or more
narrow=""
for f in $(sed -n 's/^!\[[^]]*\](\([^)]*\.png\))$/\1/p' "$top/README.md"); do
    w=$(info_json "$top/$f" width)
    [ "${w:-0}" -ge 640 ] || narrow="$narrow $f:$w"
done
[ -z "$narrow" ] && ok "the README's pictures are 640 pixels wide or more" || notok "narrow README pictures" "$narrow"
# the page in a browser, as a visitor sees it
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
    skip "the gallery in a browser" "chromium is not installed (make deps installs it)"
    exit 0
fi
shot=${TEXTURA_BUILD:-build}/artefacts/gallery.png
timeout 120 python3 "$top/tests/tools/gallery_page.py" "$chromium" "$g" "$shot" 2>"$T/cdp.err"
status=$?
if [ $status = 3 ]; then
    skip "the gallery in a browser" "$(head -c 200 "$T/cdp.err")"
elif [ $status != 0 ]; then
    notok "the gallery's browser test ran to its end" "exit $status: $(tail -c 300 "$T/cdp.err" | tr "\n" " ")"
fi
