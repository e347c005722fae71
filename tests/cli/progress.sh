#!/usr/bin/env bash
# The progress bar as a user sees it on a terminal (script(1) gives the tool one): one bar
# per job whose percentage only grows, at most ten redraws a second, the time spent and an
# estimate of the time left on each, one final line with the whole time; nothing with -q or
# when standard error is not a terminal.
. "$(dirname "$0")/../lib.sh"
top=$(cd "${TEXTURA_TOP:-.}" && pwd)
t_noise -s 256 -f 12 -S 7 -o "$T/n.exr"
# a render of seconds: a sanitizer build, 3 times slower, takes a quarter of the pixels
size=960x720
[ -n "$sanitized" ] && size=480x360
job="t_apply $top/patterns/still_life.scene -s $size --spp 2 -o $T/r.png < $T/n.exr"
script -qec "$job" /dev/null >"$T/tty.out" 2>&1
tr '\r' '\n' <"$T/tty.out" | sed 's/\x1b\[K//g' | grep -a 't_apply: \[' >"$T/bars"
n=$(grep -c '%' "$T/bars")
done_line=$(grep -a 'done in' "$T/bars")
secs=$(sed -n 's/.*done in \([0-9.]*\) s$/\1/p' <<<"$done_line")
[ "$(grep -c 'done in' "$T/bars")" = 1 ] && [ "$(tail -1 "$T/bars")" = "$done_line" ] &&
    ok "one final line: $done_line" || notok "one final line" "$(tail -3 "$T/bars")"
[ -n "$secs" ] && awk -v n="$n" -v s="$secs" 'BEGIN { exit !(n <= 10 * s + 2) }' &&
    ok "$n redraws in $secs s: at most ten a second" || notok "at most ten redraws a second" "$n in $secs s"
grep -v 'done in' "$T/bars" | grep -qv ' left$' && notok "each redraw shows the time left" "$(head -2 "$T/bars")" ||
    ok "each redraw shows the time spent and the time left"
awk '{ p = $0; sub(/^.*\] */, "", p); sub(/%.*/, "", p); if (p + 0 < last) bad = 1; last = p + 0 }
     END { exit bad }' "$T/bars" && ok "one bar: its percentage only grows" ||
    notok "one bar: its percentage only grows" "$(tr '\n' ' ' <"$T/bars" | head -c 300)"
first=$(head -1 "$T/bars" | sed 's/^.*\] *//; s/%.*//')
[ "${first:-100}" = 0 ] && ok "the bar starts at 0%" || notok "the bar starts at 0%" "$first%"
# -q, and a standard error that is not a terminal: no bar.  The bar is drawn from the
# start, so a small render shows it as well as a long one.
job="t_apply $top/patterns/still_life.scene -s 96x72 --spp 1 -o $T/r.png < $T/n.exr"
script -qec "$job" /dev/null >"$T/small.out" 2>&1
grep -aq 't_apply: \[' "$T/small.out" && ok "a small render on a terminal draws the bar too" ||
    notok "a small render draws the bar" "$(cat -v "$T/small.out" | head -c 200)"
script -qec "$job -q" /dev/null >"$T/q.out" 2>&1
grep -aq '%' "$T/q.out" && notok "-q draws no bar" "$(head -c 200 "$T/q.out")" || ok "-q draws no bar"
eval "$job" 2>"$T/err.out"
[ ! -s "$T/err.out" ] && ok "no bar when standard error is not a terminal" || notok "no bar off a terminal" "$(head -c 200 "$T/err.out")"
# Quick work leaves nothing on the screen, even on a terminal: what follows the last
# carriage return, once erased to the end of the line, is empty, and no line was ended.
script -qec "t_noise -s 64 -o $T/q.exr" /dev/null >"$T/quick.out" 2>&1
left=$(awk 'BEGIN { RS = "\r" } { last = $0 } END { gsub(/\033\[K/, "", last); printf "%s", last }' "$T/quick.out")
[ -z "$left" ] && [ "$(tr -cd '\n' <"$T/quick.out" | wc -c)" = 0 ] && ok "quick work leaves no bar" ||
    notok "quick work leaves no bar" "$(cat -v "$T/quick.out")"
