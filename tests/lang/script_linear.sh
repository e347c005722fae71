#!/usr/bin/env bash
# script_linear.sh - scripts and definitions files in linear time: 10^5 image definitions,
# 10^5 composed primitives, 10^5 cells, each within 10 s (on main each name and cell was
# compared with every one before it: over 20 s).
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1
# a sanitizer build runs several times slower and holds more (shadow memory, quarantine):
# the bounds grow with it, still far below what the quadratic parsers took
tscale=1 mscale=1
nm "$TEXTURA_BUILD/lib/libtex.a" 2>/dev/null | grep -q __asan_ && tscale=4 mscale=3
python3 - <<'PY'
n = 100000
L = ['tessellation t;', 'size 16 by 16;', 'images'] + ['   a%d = noise();' % i for i in range(n)]
open('defs.tc', 'w').write('\n'.join(L + ['end images;', 'built with', '   (1,1) a%d;' % (n - 1),
                                          'end tessellation;']) + '\n')
open('defs.tp', 'w').write(''.join('primitive p%d = 0.5*u + v\n' % i for i in range(n)))
W = 400
L = ['tessellation t;', 'size %d by %d;' % (W, n // W), 'cell 1 by 1;', 'images', '   c = noise();',
     'end images;', 'built with'] + ['   (%d,%d) c;' % (i % W + 1, i // W + 1) for i in range(n)]
open('cells.tc', 'w').write('\n'.join(L + ['end tessellation;']) + '\n')
PY
check "10^5 image definitions within 10 s" timeout $((10 * tscale)) t_compose defs.tc -o d.exr
check "10^5 composed primitives within 10 s" timeout $((10 * tscale)) t_expr --defs defs.tp 'p99999(u, v)' -s 8 -o p.exr
check "10^5 cells within 10 s" timeout $((10 * tscale)) t_compose cells.tc -o c.exr
printf 'tessellation t;\nsize 4 by 4;\ncell 2 by 2;\nbuilt with\n (1,1) noise();\n (2,1) noise();\n (1,1) noise();\nend tessellation;\n' >twice.tc
check_fails "a cell given twice" 2 t_compose twice.tc -o x.exr
grep -q "cell (1,1) is given twice (first at line 5)" "$T/.err" || notok "the first line named" "$(cat "$T/.err")"
