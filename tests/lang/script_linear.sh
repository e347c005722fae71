#!/usr/bin/env bash
# script_linear.sh - scripts and definitions files in linear time and memory: 10^5 image
# definitions, 10^5 composed primitives, 10^5 cells, each within 10 s (on main each name and
# cell was compared with every one before it: over 20 s; each composed primitive held 8 KB
# of parameter rows and searched the primitives' names for a message: 800 MB and 3 s).
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1
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
within "10^5 image definitions" 10 300000 t_compose defs.tc -o d.exr
within "10^5 composed primitives" 10 400000 t_expr --defs defs.tp 'p99999(u, v)' -s 8 -o p.exr
within "10^5 cells" 10 300000 t_compose cells.tc -o c.exr
printf 'tessellation t;\nsize 4 by 4;\ncell 2 by 2;\nbuilt with\n (1,1) noise();\n (2,1) noise();\n (1,1) noise();\nend tessellation;\n' >twice.tc
check_fails "a cell given twice" 2 t_compose twice.tc -o x.exr
grep -q "cell (1,1) is given twice (first at line 5)" "$T/.err" || notok "the first line named" "$(cat "$T/.err")"
