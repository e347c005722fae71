#!/bin/sh
# farm.sh - spread one big job over cores or hosts with GNU parallel, then assemble it.
# Every Textura tool is a deterministic process, so the pieces are made anywhere and the
# result is byte for byte the single-process one (doc/farm.md; a Slurm job array there too).
#   patterns/farm.sh map    -o OUT.exr -s WxH -n BANDS [-j JOBS] [-S HOSTS] -- GENERATOR ARGS...
#       the map in BANDS row bands (--window 0,Y,W,H), assembled by t_assemble
#   patterns/farm.sh render -o OUT.exr -s WxH -n BANDS [-j JOBS] [-S HOSTS] -- t_apply SCENE ARGS...
#       the image in BANDS row bands (--region, POV-Ray's +SR/+ER), assembled by t_assemble
#   patterns/farm.sh frames -o PREFIX -n FRAMES [-j JOBS] [-S HOSTS] -- GENERATOR ARGS...
#       frames 0..FRAMES-1 of a looping animation (--frames N --frame K) as PREFIX_K.exr
# -j: jobs per host (parallel's -j; default one per core); -S: parallel's --sshlogin list
# (e.g. 8/node1,8/node2,:), whose hosts need the tools on PATH and the inputs at the same
# absolute paths; their pieces come back with --return.  $FARM_PARALLEL adds options to
# parallel; $FARM_ASSEMBLE to t_assemble (e.g. --exr-tiles).
set -eu
usage() {
    sed -n '2,/^set /p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
    exit 2
}
[ $# -ge 1 ] || usage
mode=$1
shift
case $mode in map | render | frames) ;; -h | --help) usage ;; *)
    echo "$0: the mode must be map, render or frames (got '$mode')" >&2
    exit 2
    ;;
esac
out= size= n= jobs= hosts=
while getopts o:s:n:j:S:h opt; do
    case $opt in
    o) out=$OPTARG ;;
    s) size=$OPTARG ;;
    n) n=$OPTARG ;;
    j) jobs=$OPTARG ;;
    S) hosts=$OPTARG ;;
    *) usage ;;
    esac
done
shift $((OPTIND - 1))
[ "${1:-}" = -- ] && shift
[ $# -ge 1 ] || { echo "$0: no command after the options (-- TOOL ARGS...)" >&2; exit 2; }
[ -n "$out" ] || { echo "$0: -o is required" >&2; exit 2; }
case $n in '' | *[!0-9]* | 0) echo "$0: -n must be a whole number >= 1 (got '$n')" >&2; exit 2 ;; esac
command -v parallel >/dev/null || { echo "$0: GNU parallel is not installed (apt-get install parallel)" >&2; exit 1; }
if [ "$mode" != frames ]; then
    case $size in
    *x*) W=${size%x*} H=${size#*x} ;;
    *) W=$size H=$size ;;
    esac
    case $W$H in '' | *[!0-9]*) echo "$0: -s must be N or WxH (got '$size')" >&2; exit 2 ;; esac
    [ "$n" -le "$H" ] || { echo "$0: -n $n bands for $H rows" >&2; exit 2; }
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/farm.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# The job list: one line per piece, "Y ROWS K" for bands (rows split as evenly as they go),
# "K" for frames.
k=0
while [ "$k" -lt "$n" ]; do
    if [ "$mode" = frames ]; then
        echo "$k"
    else
        y0=$((k * H / n)) y1=$(((k + 1) * H / n))
        echo "$y0 $((y1 - y0)) $k"
    fi
    k=$((k + 1))
done >"$tmp/jobs"

# run ARGS...: the command once per job line, {1} {2} {3} standing for its fields.  parallel
# -q quotes each word, so arguments with spaces survive.  Locally the pieces go to $tmp;
# on hosts, to each host's work folder, and come back into $tmp with --return.
dir=$tmp/
[ -z "$hosts" ] || dir=
run() {
    if [ -n "$hosts" ]; then
        (cd "$tmp" && parallel --will-cite --halt now,fail=1 --colsep ' ' ${jobs:+-j "$jobs"} \
            ${FARM_PARALLEL:-} --sshlogin "$hosts" --workdir ... --return "$piece" --cleanup \
            -q "$@" :::: "$tmp/jobs")
    else
        parallel --will-cite --halt now,fail=1 --colsep ' ' ${jobs:+-j "$jobs"} \
            ${FARM_PARALLEL:-} -q "$@" :::: "$tmp/jobs"
    fi
}
case $mode in
map | render)
    piece=band_{3}.exr
    flag=--window
    [ "$mode" = map ] || flag=--region
    run "$@" -s "${W}x$H" $flag "0,{1},$W,{2}" -o "$dir$piece"
    set --
    k=0
    while [ "$k" -lt "$n" ]; do
        set -- "$@" "$tmp/band_$k.exr"
        k=$((k + 1))
    done
    t_assemble ${FARM_ASSEMBLE:-} "$@" -o "$out"
    echo "wrote $out from $n bands"
    ;;
frames)
    piece=frame_{1}.exr
    run "$@" --frames "$n" --frame {1} -o "$dir$piece"
    k=0
    while [ "$k" -lt "$n" ]; do
        mv "$tmp/frame_$k.exr" "${out}_$k.exr"
        k=$((k + 1))
    done
    echo "wrote $n frames ${out}_0.exr .. ${out}_$((n - 1)).exr"
    ;;
esac
