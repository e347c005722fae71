# tests/lib.sh - helpers for the shell tests; source it first.
#
#   check NAME CMD...             ok if CMD succeeds
#   skip NAME REASON              a check that cannot run here: "ok - NAME # skip REASON"
#                                 (tests/run counts it apart; make deps installs everything)
#   check_fails NAME STATUS CMD.. ok if CMD exits with STATUS, prints exactly one
#                                 line on stderr naming the program, and did not crash
#                                 (under `bash -c PIPELINE`, any t_* program)
#   approx A B TOL                true if |A-B| <= TOL
#   info_json MAP KEY...          a figure from t_info --json (e.g. stats 0 mean)
#   maxdiff A B                   the largest |A - B| over the colour channels
#   same NAME A B [TOL]           ok if maps A and B differ by at most TOL (default 0)
#   golden NAME MAP GOLDEN TOL    ok if MAP matches tests/golden/GOLDEN within TOL
#                                 (TEXTURA_REGOLD=1 rewrites the golden)
#   start_proto DIR [ARGS...]     start t_proto on a free port serving DIR; sets $proto_pid
#                                 and $proto_url (its address with the token); killed at exit
#   proto_up NAME                 ok NAME when t_proto printed its URL with a token, else not
#                                 ok with its output and log, and status 1
#   truncated NAME OUT CMD...     the tools that stream: CMD (a command line) reads cut.exr,
#                                 a stream cut short, on a pipe: exit 1, one line naming
#                                 standard input, and OUT (its -o) not left behind
#   stream_vlimit KB              the ulimit -v of a bounded-memory check: KB, or unlimited
#                                 in a sanitizer build (its shadow reserves terabytes)
#   stream_side N                 the side of a bounded-memory check's map: N, or 1024 in a
#                                 sanitizer build, where no limit holds and the bytes alone
#                                 are checked (many bands still; a 4096 map there cost seconds)
#   $T                            a fresh temporary folder, removed at exit
set -u
T=$(mktemp -d "${TMPDIR:-/tmp}/textura-test.XXXXXX")
trap 'rm -rf "$T"' EXIT

ok() { echo "ok - $1"; }
notok() { echo "not ok - $1${2:+: $2}"; }
skip() { echo "ok - $1 # skip $2"; }

check() {
    local name=$1
    shift
    local err
    if err=$("$@" 2>&1 >/dev/null); then ok "$name"; else notok "$name" "$(head -c 300 <<<"$err")"; fi
}

# check_fails NAME STATUS CMD...: the command must fail cleanly.
check_fails() {
    local name=$1 want=$2
    shift 2
    "$@" >"$T/.out" 2>"$T/.err" </dev/null
    local got=$? lines prog
    lines=$(wc -l <"$T/.err")
    prog=$(basename "$1")
    [ "$prog" = bash ] && prog='t_[a-z_]*' # a pipeline: any Textura tool may speak
    if [ "$got" != "$want" ]; then
        notok "$name" "exit $got, wanted $want: $(head -c 200 "$T/.err")"
    elif [ "$lines" != 1 ]; then
        notok "$name" "$lines lines on stderr: $(head -c 300 "$T/.err")"
    elif ! grep -q "^$prog: " "$T/.err"; then
        notok "$name" "message does not name $prog: $(cat "$T/.err")"
    else
        ok "$name"
    fi
}

# A sanitizer build runs several times slower and holds more (shadow memory, quarantine):
# within's bounds grow with it, still far below what a quadratic parser takes.
tscale=1 mscale=1 sanitized=""
nm "${TEXTURA_BUILD:-}/lib/libtex.a" 2>/dev/null | grep -q __asan_ && tscale=4 mscale=3 sanitized=1

# within NAME SECONDS KB CMD...: CMD succeeds in SECONDS and KB of resident memory at most
within() {
    local name=$1 s=$(($2 * tscale)) kb=$(($3 * mscale)) st
    shift 3
    /usr/bin/time -f '%M' -o "$T/.mem" timeout "$s" "$@" >/dev/null 2>"$T/.err"
    st=$?
    if [ "$st" = 0 ] && [ "$(tail -1 "$T/.mem")" -le "$kb" ]; then
        ok "$name: within $s s and $((kb / 1024)) MB ($(($(tail -1 "$T/.mem") / 1024)) MB)"
    else
        notok "$name: within $s s and $((kb / 1024)) MB" "exit $st, $(tail -1 "$T/.mem") KB: $(head -c 200 "$T/.err")"
    fi
}

approx() {
    awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'
}

# info_json MAP PATH...: python-style path into t_info --json, e.g. stats 0 mean.  The
# figures are read off t_info's lines by awk (a python3 start costs 20 ms, and the suite
# asks thousands of times); other paths go through python3's json.
info_json() {
    local map=$1
    shift
    case $#:$1:${3:-} in
    1:width: | 1:height: | 1:channels: | 1:subregions:)
        t_info --json "$map" | awk -v k="\"$1\": " 'NR == 1 { i = index($0, k); if (!i) exit 1
            v = substr($0, i + length(k)); sub(/,.*/, "", v); print v; f = 1 } END { exit !f }' ;;
    3:stats:min | 3:stats:max | 3:stats:mean | 3:stats:stddev | 3:stats:nonfinite)
        t_info --json "$map" | awk -v n="$2" -v k="\"$3\": " '/^  \{"channel"/ && c++ == n {
            v = substr($0, index($0, k) + length(k)); sub(/[,}].*/, "", v); print v; f = 1 }
            END { exit !f }' ;;
    *)
        t_info --json "$map" | python3 -c '
import json, sys
v = json.load(sys.stdin)
for k in sys.argv[1:]:
    v = v[int(k)] if isinstance(v, list) else v[k]
print(v)' "$@" ;;
    esac
}

# pfm_py: py, python3 that can import pfm: pfm.load(FILE), a map's floats (3 channels),
# width and height; pfm.px(a, w, h, x, y, ch) with y = 0 the top row.
pfm_py() {
    cat >"$T/pfm.py" <<'P'
import array, subprocess
def load(f):
    d = subprocess.run(['t_convert', '-o', '-', '--format', 'pfm', f], check=True,
                       stdout=subprocess.PIPE).stdout
    kind, size, scale, rest = d.split(b'\n', 3)
    w, h = map(int, size.split())
    nc = 3 if kind == b'PF' else 1
    a = array.array('f'); a.frombytes(rest[:w * h * nc * 4])
    if float(scale) > 0: a.byteswap()
    if nc == 1: a = array.array('f', [v for v in a for _ in range(3)])
    return a, w, h
def px(a, w, h, x, y, ch=0):
    return a[((h - 1 - y) * w + x) * 3 + ch]
P
}
py() { PYTHONPATH=$T python3 "$@"; }

# maxdiff A B: the largest |A - B| over the colour channels (sub keeps the alpha of A).
maxdiff() {
    t_op sub "$1" "$2" | t_op abs - | t_info --json | awk -F'"max": ' '/^  \{"channel"/ && n++ < 3 {
        v = $2; sub(/,.*/, "", v); if (n == 1 || v + 0 > m + 0) m = v } END { if (!n) exit 1; print m }'
}

# same NAME A B [TOL]: maps A and B agree within TOL (default 0).
same() {
    local d
    d=$(maxdiff "$2" "$3" 2>&1) && approx "$d" 0 "${4:-0}" && ok "$1" || notok "$1" "max diff $d"
}

# golden NAME MAP GOLDEN TOL: MAP matches the stored image tests/golden/GOLDEN within TOL
# (TEXTURA_REGOLD=1 rewrites it).
golden() {
    local g=${TEXTURA_TOP:-.}/tests/golden/$3
    [ -n "${TEXTURA_REGOLD:-}" ] && t_convert -o "$g" "$2"
    same "$1" "$2" "$g" "$4"
}

start_proto() {
    local dir=$1
    shift
    rm -f "$T/.proto_url" # a second start must not read the first one's URL
    t_proto -C "$dir" -p 0 "$@" >"$T/.proto_url" 2>"$T/.proto_log" &
    proto_pid=$!
    trap 'kill $proto_pid 2>/dev/null; rm -rf "$T"' EXIT
    for _ in $(seq 50); do grep -q token= "$T/.proto_url" && break; sleep 0.1; done
    proto_url=$(sed -n 's/.* on \(http:[^ ]*\)$/\1/p' "$T/.proto_url")
}

proto_up() {
    case $proto_url in
    http://127.0.0.1:*/\?token=*) ok "$1" ;;
    *) notok "$1" "$(cat "$T/.proto_url" "$T/.proto_log")"; return 1 ;;
    esac
}

truncated() {
    local name=$1 out=$2
    shift 2
    check_fails "$name: exit 1, one line" 1 bash -c "cat cut.exr | $* -o $out"
    grep -q "standard input" "$T/.err" && [ ! -e "$out" ] &&
        ok "$name: it names standard input and leaves nothing" || notok "$name" "$(cat "$T/.err")"
}
stream_vlimit() { [ -n "$sanitized" ] && echo unlimited || echo "$1"; }
stream_side() { [ -n "$sanitized" ] && echo 1024 || echo "$1"; }

# same_paths NAME SCENE: the scene rendered with packets (-j 2) and on the scalar path
# (TEXTURA_SIMD=scalar) gives the pixel-by-pixel render's bytes (TEXTURA_PACKETS=0)
same_paths() {
    local n=$1 sc=$2
    if TEXTURA_PACKETS=0 t_apply "$sc" -q -j 1 -o "$T/$n-px.pfm" &&
        t_apply "$sc" -q -j 2 -o "$T/$n-pk.pfm" &&
        TEXTURA_SIMD=scalar t_apply "$sc" -q -j 1 -o "$T/$n-pk0.pfm"; then
        cmp -s "$T/$n-px.pfm" "$T/$n-pk.pfm" && cmp -s "$T/$n-px.pfm" "$T/$n-pk0.pfm" &&
            ok "$n: packets and vector paths give the pixel-by-pixel render's bytes" ||
            notok "$n: packets against pixel by pixel" "$(maxdiff "$T/$n-px.pfm" "$T/$n-pk.pfm")"
    else
        notok "$n: renders on every path"
    fi
}
