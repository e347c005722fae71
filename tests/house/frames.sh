# frames.sh - libtex keeps frame pointers (the Makefile's FRAMES), so that a profiler's
# stack walk (perf record -g) names a hot function's callers instead of taking whatever
# lies on the stack for them: every tex_ function of t_apply that calls another sets up
# its frame (mov %rsp,%rbp) before its first call.
. "$(dirname "$0")/../lib.sh"
bin=$TEXTURA_BUILD/bin/t_apply
if ! command -v objdump >/dev/null; then
    ok "frame pointers # skip no objdump"
    exit 0
fi
objdump -d --no-show-raw-insn "$bin" >"$T/dis" 2>"$T/err" || {
    notok "objdump reads t_apply" "$(head -c 200 "$T/err")"
    exit 0
}
awk '
/^[0-9a-f]+ <[^>]*>:$/ { name = $2; gsub(/[<>:]/, "", name)
    mine = name ~ /^tex_/ && name !~ /\.cold$/; fp = 0; seen = 0; next }
mine && !seen && /mov +%rsp,%rbp/ { fp = 1 }
mine && !seen && /\tcall / { seen = 1; callers++; if (!fp) { bad++; if (bad <= 3) first = first " " name } }
END { print callers + 0, bad + 0, first }' "$T/dis" >"$T/count"
read -r callers bad first <"$T/count"
[ "$callers" -gt 100 ] && ok "t_apply has $callers tex_ functions that call others" ||
    notok "t_apply's tex_ functions that call others" "$callers"
[ "$bad" = 0 ] && ok "each sets up its frame pointer before its first call" ||
    notok "each sets up its frame pointer before its first call" "$bad do not:$first"
