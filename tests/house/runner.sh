#!/usr/bin/env bash
# runner.sh - tests/run itself, on a tree of its own: counts, skips, a failing file, a
# file over its budget (TEXTURA_TEST_BUDGET=1), a stable order whatever ends first,
# the slowest files, the logs and the closing line.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
f=$T/tree
mkdir -p "$f/tests"
printf '#!/bin/sh\necho "ok - one"\necho "ok - two # skip not here"\n' >"$f/tests/test_a"
printf '#!/bin/sh\nsleep 1.5\necho "ok - slow"\n' >"$f/tests/test_b"
printf '#!/bin/sh\necho "not ok - broken: why"\nexit 1\n' >"$f/tests/test_c"
chmod +x "$f/tests/"test_*
TEXTURA_TEST_BUDGET=1 "$top/tests/run" -j 3 "$f:test_a,test_b,test_c" >"$T/out" 2>&1
st=$?
[ "$st" != 0 ] && ok "tests/run fails when a file fails" || notok "tests/run's exit" "$st"
[ "$(tail -1 "$T/out")" = "2 passed, 2 failed, 1 skipped" ] && ok "the closing line counts passes, failures and skips apart" ||
    notok "closing line" "$(tail -1 "$T/out")"
grep -q "^not ok - test_b took 1\.[0-9] s, over its budget of 1 s$" "$T/out" &&
    ok "a file over its budget fails, naming its time" || notok "budget" "$(grep test_b "$T/out")"
# test_b ends last, yet prints between test_a and test_c
order=$(grep -o '^[^ ]*tree *test_[abc]' "$T/out" | awk '{ print $2 }' | tr '\n' ' ')
[ "$order" = "test_a test_b test_c " ] && ok "files print in a stable order" || notok "order" "$order"
awk '/^Slowest files:/ { getline; print; exit }' "$T/out" | grep -q 'test_b$' &&
    ok "the slowest file heads the slowest list" || notok "slowest list" "$(grep -A2 Slowest "$T/out")"
grep -q '^not ok - broken: why$' "$f/test-logs/test_c.log" && ok "each file's output is kept in BUILD/test-logs" ||
    notok "test-logs"
