#!/usr/bin/env bash
# tests/fuzz/campaign.sh [-j JOBS] [-n EXECUTIONS] [EXECUTIONS] [SECONDS] [TARGET...] - the
# long fuzz run: each target (default: every fuzz_* in build/fuzz, built by `make fuzz`)
# runs in pieces of at most SECONDS (default 600) until the ledger tests/fuzz/campaign.log
# ($LEDGER) holds EXECUTIONS (default 10^7; -n 100000 for a short run) executions for it
# since its last crash.  At the end each target's count is printed and written to the
# ledger as a "# total" line.  Pieces
# grow the scratch corpus tests/fuzz/corpus-NAME (not kept; the seeds are), JOBS
# targets at a time (default 1).  A crash stops its target: the input is kept as
# tests/fuzz/crash-NAME-*, the ledger says so, and the exit status is 1.  To stop
# early, send SIGINT to the running fuzzers (and to those started after them):
# each stops its target with its count recorded as "interrupted".
# A timeout (an input running past 60 s of wall time, which nice 19 on a busy
# machine stretches) stops its target too, as "timeout", but its executions count:
# it is a slow input to look at, not a crash.
# Ledger lines: "DATE COMMIT fuzz_NAME EXECUTIONS SECONDS STATUS", the status ok,
# interrupted, timeout or crash.  Entropic scheduling is off: its bookkeeping
# (UpdateFeatureFrequency) took half of every run of the larger targets, and without
# it they run 2.4 times as many inputs; so is rereading the corpus directory (a
# tenth), which only other processes write.
set -u
jobs=1 want=
while getopts j:n: o; do
    case $o in
    j) jobs=$OPTARG ;;
    n) want=$OPTARG ;;
    *) echo "usage: campaign.sh [-j JOBS] [-n EXECUTIONS] [EXECUTIONS] [SECONDS] [TARGET...]" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
whole() { case $1 in '' | *[!0-9]*) return 1 ;; esac; }
# the positional form: EXECUTIONS (unless -n gave it), then SECONDS, where numbers are
[ -z "$want" ] && whole "${1:-}" && { want=$1; shift; }
secs=600
whole "${1:-}" && { secs=$1; shift; }
want=${want:-10000000}
whole "$want" && whole "$jobs" || { echo "campaign.sh: -n and -j take whole numbers" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
fuzz=${FUZZDIR:-$here/../../build/fuzz}
ledger=${LEDGER:-$here/campaign.log}
commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)

# executions of a target in the ledger since its last crash ("# total" lines are summaries)
done_runs() {
    awk -v t="$1" '$1 != "#" && $3 == t { n = ($6 == "crash") ? 0 : n + $4 } END { print n + 0 }' "$ledger" 2>/dev/null || echo 0
}

one() {
    local name=$1 t=$fuzz/$1 have left log st runs
    local seeds=$here/seeds-${name#fuzz_} corpus=$here/corpus-${name#fuzz_}
    mkdir -p "$corpus"
    while have=$(done_runs "$name"); [ "$have" -lt "$want" ]; do
        left=$((want - have))
        log=$(mktemp "${TMPDIR:-/tmp}/textura-campaign.XXXXXX")
        "$t" -entropic=0 -reload=0 -runs="$left" -max_total_time="$secs" -timeout=60 -rss_limit_mb=2048 \
            -print_final_stats=1 -artifact_prefix="$here/crash-${name#fuzz_}-" \
            "$corpus" "$seeds" >"$log" 2>&1
        st=$?
        runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
        if [ "$st" = 0 ] && [ -n "$runs" ]; then
            echo "$(date -u +%FT%TZ) $commit $name $runs $secs ok" >>"$ledger"
            rm -f "$log"
        elif [ "$st" = 72 ] && [ -n "$runs" ]; then # libFuzzer's exit on SIGINT
            echo "$(date -u +%FT%TZ) $commit $name $runs $secs interrupted" >>"$ledger"
            rm -f "$log"
            echo "ok - $name: interrupted at $(done_runs "$name") executions"
            return 0
        elif [ "$st" = 70 ] && [ -n "$runs" ]; then # a slow input: kept, to be looked at
            echo "$(date -u +%FT%TZ) $commit $name $runs $secs timeout" >>"$ledger"
            echo "not ok - $name: an input ran past the timeout (log $log)"
            grep -E 'Test unit written' "$log" | head -1
            return 1
        else
            echo "$(date -u +%FT%TZ) $commit $name ${runs:-0} $secs crash" >>"$ledger"
            echo "not ok - $name: exit $st (log $log)"
            grep -E 'ERROR|runtime error|Test unit written' "$log" | head -5
            return 1
        fi
    done
    echo "ok - $name: $(done_runs "$name") executions"
}
export -f one done_runs
export fuzz here ledger want secs commit

[ $# -gt 0 ] || set -- $(cd "$fuzz" && ls fuzz_* 2>/dev/null)
[ $# -gt 0 ] || { echo "not ok - no fuzz targets in $fuzz (make fuzz)"; exit 1; }
export OMP_NUM_THREADS=1
parallel --line-buffer -j "$jobs" one ::: "$@"
st=$?
for name in "$@"; do # each target's count, on the screen and in the ledger
    echo "# total $(date -u +%FT%TZ) $commit $name $(done_runs "$name") of $want" | tee -a "$ledger"
done
exit $st
