# colour_tools.sh - t_palette, t_filter and t_remap from the command line
. "$(dirname "$0")/../lib.sh"
export TEXTURA_PALETTES="$TEXTURA_TOP/palettes"

t_noise -s 64 -o "$T/n.exr"

# t_palette: names, files, ranges, the colour editor, bad palettes
check "t_palette marble colours a map" t_palette marble -o "$T/m.exr" "$T/n.exr"
[ "$(info_json "$T/m.exr" channels)" = 3 ] && ok "a palette gives RGB" || notok "a palette gives RGB"
check "--palette NAME MAP" t_palette --palette viridis -o "$T/v.exr" "$T/n.exr"
t_palette --from '#000000' --to '#ffffff' --stops 5 -o "$T/bw.pal" && ok "--from/--to writes a palette" || notok "--from/--to"
grep -q '^0.5 0.5 0.5 0.5$' "$T/bw.pal" && ok "the editor's middle stop is grey" || notok "middle stop" "$(cat "$T/bw.pal")"
t_palette "$T/bw.pal" --range 0,1 -o "$T/g.exr" "$T/n.exr"
a=$(info_json "$T/g.exr" stats 0 mean) b=$(info_json "$T/n.exr" stats 0 mean)
approx "$a" "$b" 1e-5 && ok "a black-white palette over 0,1 is the identity ($a)" || notok "identity palette" "$a vs $b"
t_palette "$T/bw.pal" -o "$T/a.exr" "$T/n.exr"
# a file named without '/' or .pal, in the working folder; a palette's name still wins
cp "$T/bw.pal" "$T/ramp.gpl" && cp "$T/bw.pal" "$T/marble"
(cd "$T" && t_palette ramp.gpl -o g2.exr n.exr && t_palette marble -o m2.exr n.exr) ||
    notok "t_palette FILE without .pal"
same "t_palette ramp.gpl: a file of that name" "$T/a.exr" "$T/g2.exr"
same "t_palette marble: the shipped palette before ./marble" "$T/m.exr" "$T/m2.exr"
mkdir "$T/dirpal"
check_fails "a folder is no palette file: unknown palette, exit 2" 2 bash -c "cd '$T' && t_palette dirpal n.exr"
grep -q "unknown palette 'dirpal'" "$T/.err" && ok "the message names it" || notok "folder message" "$(cat "$T/.err")"
t_palette greys --range 0.25,0.5 --outside repeat -o "$T/r.exr" "$T/n.exr"
[ "$(info_json "$T/r.exr" stats 0 max)" != 1 ] && ok "--outside repeat wraps" || notok "--outside repeat"
printf '0 #000000\n0.5 #ffffff\n0.4 #808080\n' >"$T/bad.pal"
check_fails "unsorted stops: exit 1, file:line" 1 t_palette "$T/bad.pal" "$T/n.exr"
grep -q "bad.pal:3: stops out of order" "$T/.err" && ok "the message names file and line" || notok "file:line" "$(cat "$T/.err")"
printf '0 #12345z\n' >"$T/hex.pal"
check_fails "a bad hex colour" 1 t_palette "$T/hex.pal" "$T/n.exr"
printf '# nothing\n' >"$T/empty.pal"
check_fails "an empty palette" 1 t_palette "$T/empty.pal" "$T/n.exr"
# the one whole-file reader's limit (tex_read_text): a palette is text of at most 4 MiB
head -c 4200000 /dev/zero | tr '\0' '#' >"$T/huge.pal"
check_fails "a palette file over 4 MiB" 1 t_palette "$T/huge.pal" "$T/n.exr"
grep -q 'huge.pal: larger than 4194304 bytes for a palette' "$T/.err" &&
    ok "the size limit names the file and the limit" || notok "palette size limit" "$(cat "$T/.err")"
check_fails "an unknown palette name" 2 t_palette no_such_palette "$T/n.exr"
check_fails "--range with MIN >= MAX" 2 t_palette marble --range 1,0 "$T/n.exr"
check_fails "--from without --to" 2 t_palette --from '#fff'
check_fails "a bad --to colour" 2 t_palette --from '#fff' --to 'pink'
[ ! -e "$T/none.exr" ] && ok "no output file after a failure" || notok "partial output"

# t_filter
check "t_filter blur" t_filter blur --sigma 2 -o "$T/b.exr" "$T/n.exr"
check "options before the operation" t_filter --sigma 2 --edge wrap -o "$T/b2.exr" blur "$T/n.exr"
t_info "$T/b.exr" | grep -q "t_filter blur --sigma 2" && ok "the history keeps the operation" || notok "history"
# the same command line (history) with 1 and 2 threads
OMP_NUM_THREADS=1 t_filter blur --sigma 3 "$T/n.exr" >"$T/j1.exr"
OMP_NUM_THREADS=2 t_filter blur --sigma 3 "$T/n.exr" >"$T/j2.exr"
cmp -s "$T/j1.exr" "$T/j2.exr" && ok "blur: 1 and 2 threads give the same bytes" || notok "blur -j"
OMP_NUM_THREADS=1 t_filter noise -S 4 "$T/n.exr" >"$T/j1.exr"
OMP_NUM_THREADS=2 t_filter noise -S 4 "$T/n.exr" >"$T/j2.exr"
cmp -s "$T/j1.exr" "$T/j2.exr" && ok "noise: 1 and 2 threads give the same bytes" || notok "noise -j"
for op in box smooth sharpen sobel edges emboss median noise normal gradient; do
    check "t_filter $op" t_filter $op -o "$T/$op.exr" "$T/n.exr"
done
[ "$(info_json "$T/normal.exr" channels)" = 3 ] && ok "normal gives RGB" || notok "normal channels"
check_fails "sigma 0" 2 t_filter blur --sigma 0 "$T/n.exr"
check_fails "a kernel larger than the map" 2 t_filter blur --sigma 20 "$T/n.exr"
check_fails "an unknown operation" 2 t_filter frobnicate "$T/n.exr"
check_fails "a missing input" 1 t_filter blur "$T/missing.exr"

# t_remap
t_remap --bias 0.25 -o "$T/bias.exr" "$T/n.exr"
check "t_remap --bias" test -s "$T/bias.exr"
t_remap --clamp 0.4,0.6 -o "$T/c.exr" "$T/n.exr"
lo=$(info_json "$T/c.exr" stats 0 min) hi=$(info_json "$T/c.exr" stats 0 max)
approx "$lo" 0.4 1e-6 && approx "$hi" 0.6 1e-6 && ok "--clamp keeps values in range" || notok "--clamp" "$lo $hi"
t_remap --invert "$T/n.exr" | t_remap --invert -o "$T/ii.exr"
a=$(info_json "$T/ii.exr" stats 0 mean) b=$(info_json "$T/n.exr" stats 0 mean)
approx "$a" "$b" 1e-6 && ok "invert twice is the identity" || notok "invert twice" "$a $b"
check_fails "bias 1" 2 t_remap --bias 1 "$T/n.exr"
check_fails "levels with 3 values" 2 t_remap --levels 0,1,0 "$T/n.exr"

# A pipeline: noise -> blur -> gain -> palette -> PNG
t_noise -s 64 | t_filter blur --sigma 1.5 --edge wrap | t_remap --perlin-gain 0.7 | t_palette fire -o "$T/fire.png" &&
    ok "pipeline noise | blur | remap | palette -> png" || notok "pipeline"
