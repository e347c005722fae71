# house.sh - the house rules that a reader of libtex relies on, checked on the tree:
# CPU-specific code only in the layers' x86/ folders, no function body written as a macro
# (no macro over 10 lines), no code that branches on a parameter row's name (a row names
# its reader), and every operator of the languages defined once (lang/expr.h).
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}

# intrinsics FILE...: the lines of the files that use x86 intrinsics or their types
intrinsics() {
    grep -nE '_mm(256|512)?_[a-z0-9_]+\(|__m(128|256|512)[di]?\b|__mmask(8|16|32|64)\b|<(imm|x86|[a-z]*m)intrin\.h>|\bTEX_(AVX2|AVX512|VBMI)\b' "$@" \
        /dev/null 2>/dev/null
}
portable() { # the libtex sources outside x86/ folders, but the one that defines the targets
    find "$1" \( -name '*.[ch]' -o -name '*.cpp' \) ! -path '*/x86/*' | sort
}
bad=$(intrinsics $(portable "$top/libtex"))
[ -z "$bad" ] && ok "no x86 intrinsic outside an x86/ folder" \
    || notok "x86 intrinsics outside x86/" "$(head -5 <<<"$bad")"

# long_macros FILE...: "file:line: NAME N lines" for each #define over 10 lines
long_macros() {
    awk 'FNR == 1 { n = 0 }
         n > 0 { n++; if ($0 !~ /\\$/) { if (n > 10) printf "%s:%d: %s %d lines\n", FILENAME, at, name, n; n = 0 } ; next }
         /^[ \t]*#[ \t]*define[ \t]/ { name = $2; sub(/\(.*/, "", name); at = FNR; n = 1
                                       if ($0 !~ /\\$/) n = 0 }' "$@"
}
bad=$(long_macros $(find "$top/libtex" -name '*.[ch]' -o -name '*.def' | sort))
[ -z "$bad" ] && ok "no macro over 10 lines in libtex" || notok "macros over 10 lines" "$(head -5 <<<"$bad")"

bad=$(grep -rnE 'strcmp\((p|row|r)->name, *"' "$top/libtex" /dev/null)
[ -z "$bad" ] && ok "no code branches on a parameter row's name" \
    || notok "code tests a row's name" "$(head -3 <<<"$bad")"

# operators DIR: an operator of lang/expr.h computed outside it (the renderer computes them
# through tex_expr_op, defining none of its own)
operators() {
    grep -rnE 'case TEX_EOP_[A-Z]+: *([a-z]+(\[k\])? *=|return) *[^;]*[-+*/]' "$1" /dev/null |
        grep -v 'lang/expr\.h:'
}
bad=$(operators "$top/libtex")
[ -z "$bad" ] && ok "every operator of the languages is defined once (lang/expr.h)" \
    || notok "an operator defined again" "$(head -3 <<<"$bad")"

# The checks must find what they look for: a copy of the tree with one of each planted.
cp -R "$top/libtex" "$T/libtex"
printf '#include <immintrin.h>\nstatic __m256 f(__m256 a) { return _mm256_add_ps(a, a); }\n' \
    >>"$T/libtex/ops/remap.c"
[ -n "$(intrinsics $(portable "$T/libtex"))" ] && [ -z "$(intrinsics "$T/libtex/base/map.c")" ] \
    && ok "the intrinsics check finds a planted kernel" || notok "the intrinsics check finds a planted kernel"
{ printf '#define BIG(x) \\\n'; for i in $(seq 10); do printf '    x; \\\n'; done; printf '    x\n'; } \
    >>"$T/libtex/base/map.c"
printf '#define SMALL(x) \\\n    x\n' >>"$T/libtex/base/rng.c"
printf 'static double op(int o, double a, double b)\n{\n    switch (o) {\n    case TEX_EOP_MUL: return a * b;\n    }\n}\n' \
    >>"$T/libtex/render/appfn.c"
grep -q 'render/appfn.c:.*TEX_EOP_MUL' <<<"$(operators "$T/libtex")" \
    && ok "the operator check finds a planted definition" || notok "the operator check finds a planted definition"
bad=$(long_macros "$T/libtex/base/map.c" "$T/libtex/base/rng.c")
[ "$(wc -l <<<"$bad")" = 1 ] && grep -q 'map.c:[0-9]*: BIG 12 lines' <<<"$bad" \
    && ok "the macro check finds a planted 12-line macro and passes a short one" \
    || notok "the macro check finds a planted macro" "$bad"

# The tests follow the layers: each test file sits in the folder of the layer it tests
# (tests/base ... tests/cli), or in tools/ (end to end) or house/ (these checks); tests/run
# finds them there and nowhere else.
stray=$(cd "$top/tests" && ls ./*.sh ./*.c ./*/*.sh ./*/test_*.c 2>/dev/null |
    grep -vE '^\./(lib\.sh|(fuzz|bench)/[a-z_]+\.sh|(base|io|prim|ops|lang|render|cli|tools|house)/(test_[a-z0-9_]+\.c|[a-z0-9_]+\.sh))$')
[ -z "$stray" ] && ok "every test file sits in its layer's folder, tools/ or house/" \
    || notok "test files outside the layers' folders" "$stray"
for l in base io prim ops lang render cli; do
    [ -n "$(ls "$top/tests/$l"/test_*.c 2>/dev/null)" ] || notok "tests/$l has no unit test"
done
