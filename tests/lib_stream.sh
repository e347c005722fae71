# tests/lib_stream.sh - helpers for the tests of tools that stream; source it after lib.sh.
#
#   truncated NAME OUT CMD...  CMD (a command line) reads cut.exr, a stream cut short that
#                           the caller made, on a pipe: exit 1, one line naming standard
#                           input, and OUT (its -o) not left behind
#   stream_vlimit KB        the address-space limit (ulimit -v) for a bounded-memory check:
#                           KB, or unlimited in a sanitizer build (its shadow reserves TBs)
truncated() {
    local name=$1 out=$2
    shift 2
    check_fails "$name: exit 1, one line" 1 bash -c "cat cut.exr | $* -o $out"
    grep -q "standard input" "$T/.err" && [ ! -e "$out" ] &&
        ok "$name: it names standard input and leaves nothing" || notok "$name" "$(cat "$T/.err")"
}
stream_vlimit() {
    nm "$TEXTURA_BUILD/lib/libtex.a" 2>/dev/null | grep -q __asan_ && echo unlimited || echo "$1"
}
