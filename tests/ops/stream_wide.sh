#!/usr/bin/env bash
# stream_wide.sh - maps 65536 wide stream in bounded memory: a band of wide rows is 16 to 64
# rows of 8 MiB at most, the EXR writer's band and a compressed batch likewise (issue 58)
. "$(dirname "$0")/../lib.sh"
# A 65536-wide map: each stage holds tens of MiB, not a hundred and more (64 rows of 768 KiB
# were 48 MiB a band: the RGB blur held 237 MiB, t_palette 118 MiB). RSS, not ulimit -v:
# threads reserve address space they never touch. Not under a sanitizer (its shadow memory).
if ! nm "$TEXTURA_BUILD/lib/libtex.a" 2>/dev/null | grep -q __asan_; then
    t_noise -s 65536x300 -f 8 | /usr/bin/time -f %M -o "$T/m1" t_palette marble --range 0,1 |
        /usr/bin/time -f %M -o "$T/m2" t_filter blur --sigma 2 |
        /usr/bin/time -f %M -o "$T/m3" t_remap --gamma 2 | cat >"$T/wide.exr"
    # a ZIP file: a chunk is 16 rows (12 MiB here), two compressed at once (was 249 MB)
    /usr/bin/time -f %M -o "$T/m4" t_convert --compression zip -o "$T/wide_zip.exr" <"$T/wide.exr"
    for k in "1 t_palette 64000" "2 t_filter_blur 96000" "3 t_remap 64000" "4 t_convert_zip 160000"; do
        set -- $k
        kb=$(tail -1 "$T/m$1")
        [ "$kb" -le "$3" ] && ok "65536 wide: $2 within $(($3 / 1000)) MB ($((kb / 1000)) MB)" ||
            notok "65536 wide: $2 within $(($3 / 1000)) MB" "$kb KB"
    done
    t_info "$T/wide.exr" | grep -q "65536x300, 3 channels" && ok "65536 wide: the rows pass whole" ||
        notok "65536 wide: the rows pass whole" "$(t_info "$T/wide.exr" 2>&1 | head -2)"
else
    skip "65536 wide: peak RSS" "a sanitizer build (its shadow memory)"
fi
