# tests/bench/lib.sh - helpers for benchmark scripts; source it first.
#
#   median_time N CMD...   run CMD (a shell string) N times, print the median wall seconds
#   ratio A B              A/B with 3 significant digits
set -u
BT=$(mktemp -d "${TMPDIR:-/tmp}/textura-bench.XXXXXX")
trap 'rm -rf "$BT"' EXIT

median_time() {
    local n=$1 cmd=$2 i
    for ((i = 0; i < n; i++)); do
        local s e
        s=$(date +%s.%N)
        bash -c "$cmd" >/dev/null 2>&1
        e=$(date +%s.%N)
        echo "$e - $s" | bc -l
    done | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'
}

ratio() {
    awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3g\n", (b > 0) ? a / b : 0 }'
}
