#!/usr/bin/env bash
# parse_linear.sh - scene parsers in linear time and memory: 10^5 lights and surfaces,
# 2 10^5 materials, each parsed within 10 s (on main: 100,000 lights failed at 6 GB, each
# light copying the array before it; 2 10^5 materials took over 20 s, each name compared
# with every one before it).
. "$(dirname "$0")/../lib.sh"
cd "$T" || exit 1
python3 - <<'PY'
n = 100000
head = ['image 8 8', 'camera { eye 0 0 -3 look 0 0 0 }']
lights = ['light point { position %d 5 -5 intensity 0.00001 }' % (i % 7) for i in range(n)]
open('lights.scene', 'w').write('\n'.join(head + lights + ['sphere { radius 1 }']) + '\n')
surfs = ['surface s%d { Kd 0.5 }' % i for i in range(20000)]
open('surfaces.scene', 'w').write('\n'.join(head + ['light point { position 0 5 -5 }'] + surfs +
                                            ['sphere { radius 1 surface s19999 }']) + '\n')
m = 200000
open('mats.txt', 'w').write(''.join('material m%d dielectric\ncauchy 1.5 0.004\nend\n' % i
                                    for i in range(m)))
open('mats.scene', 'w').write('\n'.join(head + ['materials "mats.txt"', 'light point { position 0 5 -5 }',
    'surface g { model cook-torrance material m%d facets beckmann 0.1 }' % (m - 1),
    'sphere { radius 1 surface g }']) + '\n')
PY
within "10^5 point lights" 10 400000 t_apply lights.scene -o l.exr
within "2 10^4 surfaces" 10 200000 t_apply surfaces.scene -o s.exr
within "2 10^5 materials" 10 1000000 t_apply mats.scene -o m.exr
# the checks that changed stay: a name defined twice is refused at its line
printf 'material a dielectric\nior 1.5\nend\nmaterial b dielectric\nior 1.6\nend\nmaterial a dielectric\nior 1.5\nend\n' >dup.txt
sed 's/mats.txt/dup.txt/;s/m199999/b/' mats.scene >dup.scene
check_fails "a material defined twice" 2 t_apply dup.scene -o d.exr
grep -q "dup.txt:7: material 'a' defined twice" "$T/.err" || notok "the second definition's line" "$(cat "$T/.err")"
