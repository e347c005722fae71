#!/usr/bin/env bash
# tests/fuzz/smoke.sh FUZZDIR [SECONDS] - the CI smoke run (make fuzz-smoke):
# every libFuzzer target in FUZZDIR (clang, ASan+UBSan, built by `make fuzz`)
# runs SECONDS (default 30), FUZZ_JOBS at a time (default: one per core), over
# its seed corpus tests/fuzz/seeds-NAME, from a
# fixed random seed (a red run can be repeated); new inputs go to a scratch
# corpus, not into the seeds.  Prints one line per target, "ok - fuzz_NAME:
# N runs" or "not ok - ...", then "fuzz: N passed, N failed", and fails if any failed.
set -u
dir=${1:?usage: smoke.sh FUZZDIR [SECONDS]}
secs=${2:-30}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/textura-fuzz.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
jobs=${FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}
# one NAME: the target's run, its line into $tmp/NAME.line, a failure's input kept
one() {
    local t=$1 name seeds st runs nseeds
    name=$(basename "$t")
    seeds="$here/seeds-${name#fuzz_}"
    mkdir -p "$tmp/$name"
    "$t" -seed=1 -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$tmp/$name-" "$tmp/$name" ${seeds:+"$seeds"} >"$tmp/$name.log" 2>&1
    st=$?
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$tmp/$name.log" | tail -1)
    nseeds=$(find "$seeds" -type f 2>/dev/null | wc -l)
    if [ "$st" = 0 ] && [ "${runs:-0}" -lt "$nseeds" ]; then
        echo "not ok - $name: ${runs:-0} runs in ${secs} s, fewer than its $nseeds seeds" >"$tmp/$name.line"
    elif [ "$st" = 0 ]; then
        echo "ok - $name: ${runs:-?} runs in ${secs} s (its $nseeds seeds and more)" >"$tmp/$name.line"
    else
        { echo "not ok - $name: exit $st after ${runs:-?} runs"
          grep -E 'ERROR|runtime error|Test unit written' "$tmp/$name.log" | head -5; } >"$tmp/$name.line"
        cp "$tmp/$name"-* "$here/" 2>/dev/null # keep the crashing input beside the targets
    fi
}
# FUZZ_JOBS targets at a time (default: one per core), printed in order
names=() running=0
for t in "$dir"/fuzz_*; do
    [ -x "$t" ] || continue
    names+=("$(basename "$t")")
    if [ "$running" -ge "$jobs" ]; then wait -n; running=$((running - 1)); fi
    one "$t" &
    running=$((running + 1))
done
wait
[ ${#names[@]} -gt 0 ] || { echo "not ok - no fuzz targets in $dir (make fuzz)"; exit 1; }
pass=0 fail=0
for name in "${names[@]}"; do
    cat "$tmp/$name.line" 2>/dev/null || echo "not ok - $name: no result"
    if grep -q '^ok ' "$tmp/$name.line" 2>/dev/null; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
done
echo "fuzz: $pass passed, $fail failed"
[ "$fail" = 0 ]
