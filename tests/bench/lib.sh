# tests/bench/lib.sh - helpers for benchmark scripts; source it first.
#
#   median_time N CMD      median wall seconds of N runs of CMD, timed by hyperfine
#                          (no shell for a plain command; for a pipeline hyperfine
#                          subtracts the shell's own start-up)
#   cpu_time CMD...        user + system CPU seconds of CMD and its children (stdout
#                          discarded), to the millisecond (bash's times, not time(1)'s
#                          10 ms); redirect stdin at the call
#   median                 the median of the numbers on standard input
#   ratio A B              A/B with 3 significant digits
#   calc EXPR              awk arithmetic, e.g. calc "2 * 3.5"
#   one_cpu CMD...         CMD on one CPU, the same for every call (the last this script may
#                          use; taskset): single-threaded runs compared in pairs then compare
#                          programs, not two CPUs, which on a shared virtual machine may run at
#                          different speeds for minutes (25 % apart here, by turns)
set -u
BT=$(mktemp -d "${TMPDIR:-/tmp}/textura-bench.XXXXXX")
trap 'rm -rf "$BT"' EXIT

median_time() {
    local n=$1 cmd=$2 shell=()
    case $cmd in *'|'* | *'>'* | *'<'* | *';'*) ;; *) shell=(-N) ;; esac
    hyperfine "${shell[@]}" --runs "$n" --warmup 1 --export-json "$BT/h.json" "$cmd" \
        >/dev/null 2>&1 || { echo 0; return; }
    python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["results"][0]["median"])' "$BT/h.json"
}

cpu_time() {
    ("$@" >/dev/null || exit 1; times) | awk 'function s(t, a) { split(t, a, "m"); return a[1] * 60 + a[2] }
        NR == 2 { printf "%.3f\n", s($1) + s($2) }'
}

median() {
    sort -g | awk '{ a[NR] = $1 } END { if (NR) print a[int((NR + 1) / 2)] }'
}

ratio() {
    awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3g\n", (b > 0) ? a / b : 0 }'
}

calc() {
    awk "BEGIN { printf \"%.4g\n\", $1 }"
}

BENCH_CPU=$(taskset -pc $$ 2>/dev/null | sed 's/.*: //; s/.*[,-]//')
one_cpu() {
    if [ -n "$BENCH_CPU" ]; then taskset -c "$BENCH_CPU" "$@"; else "$@"; fi
}
