#!/usr/bin/env bash
# bubble.sh - t_bubble: values, seams, determinism, cells, bad input
. "$(dirname "$0")/../lib.sh"

# pfm FILE EXPR: evaluate a python expression over the map as rows m[y][x].
pfm() {
    python3 - "$@" <<'PY'
import struct, sys
d = open(sys.argv[1], 'rb').read()
head, rest = d.split(b'\n', 1)
dims, rest = rest.split(b'\n', 1)
scale, data = rest.split(b'\n', 1)
w, h = map(int, dims.split())
v = struct.unpack(('<' if float(scale) < 0 else '>') + '%df' % (w * h), data[:4 * w * h])
m = [v[(h - 1 - y) * w:(h - y) * w] for y in range(h)]  # PFM stores the bottom row first
print(eval(sys.argv[2]))
PY
}

for v in bubble f1 f2 f2-f1 cell; do
    t_bubble -s 64 -c 30 --value "$v" -o "$T/$v.pfm"
    r=$(pfm "$T/$v.pfm" 'min(min(r) for r in m) >= 0 and max(max(r) for r in m) <= 1 and max(max(r) for r in m) > min(min(r) for r in m)')
    [ "$r" = True ] && ok "--value $v lies in [0,1] and varies" || notok "--value $v lies in [0,1]" "$r"
done

# The bubble shading is light at the points (centres) and dark at the borders.
t_bubble -s 128 -c 20 -o "$T/b.pfm"
t_bubble -s 128 -c 20 --value f2-f1 -o "$T/e.pfm"
r=$(pfm "$T/b.pfm" 'max(max(r) for r in m) > 0.95 and min(min(r) for r in m) < 0.3')
[ "$r" = True ] && ok "bubble: bright centres, dark borders" || notok "bubble: bright centres, dark borders" "$r"

# The same seed gives the same bytes on 1 and 2 threads, for every search.
for s in grid kdtree brute; do
    t_bubble -s 96x80 -c 300 --value f2 --search "$s" -j 1 -o "$T/j1-$s.pfm"
    t_bubble -s 96x80 -c 300 --value f2 --search "$s" -j 2 -o "$T/j2-$s.pfm"
    check "--search $s: -j 1 and -j 2 give the same map" cmp "$T/j1-$s.pfm" "$T/j2-$s.pfm"
done
# and at every SIMD level: the grid's AVX2 candidate lanes against SSE2's
TEXTURA_SIMD=scalar t_bubble -s 96x80 -c 300 --value f2 --search grid -j 2 -o "$T/s-grid.pfm"
check "--search grid: TEXTURA_SIMD=scalar gives the same map" cmp "$T/j1-grid.pfm" "$T/s-grid.pfm"
check "grid and kd-tree give the same map" cmp "$T/j1-grid.pfm" "$T/j1-kdtree.pfm"
check "grid and brute force give the same map" cmp "$T/j1-grid.pfm" "$T/j1-brute.pfm"
# Far more points than pixels: the grid goes without its candidate lists, and agrees.
for s in grid kdtree; do
    t_bubble -s 40x30 -c 30000 --value f2-f1 --search "$s" -o "$T/many-$s.pfm"
done
check "30000 points in 40x30 pixels: grid and kd-tree agree" cmp "$T/many-grid.pfm" "$T/many-kdtree.pfm"
t_bubble -s 40x30 -c 30000 --value f2-f1 --search grid -j 2 -o "$T/many-j2.pfm"
check "and -j 2 agrees" cmp "$T/many-grid.pfm" "$T/many-j2.pfm"
t_bubble -s 96x80 -c 300 --distribution cluster --metric chebyshev --size-spread 0.5 \
    --axis-spread 0.5 --tile -j 1 -o "$T/c1.pfm"
t_bubble -s 96x80 -c 300 --distribution cluster --metric chebyshev --size-spread 0.5 \
    --axis-spread 0.5 --tile -j 2 -o "$T/c2.pfm"
check "clusters, radii, Chebyshev, tile: -j 1 and -j 2 agree" cmp "$T/c1.pfm" "$T/c2.pfm"

# --tile: the jump across the seams is no larger than between neighbouring pixels.
seam='max(max(abs(r[0] - r[-1]) for r in m), max(abs(a - b) for a, b in zip(m[0], m[-1]))) <= 1.01 * max(max(abs(r[x] - r[x + 1]) for x in range(len(r) - 1)) for r in m + [list(c) for c in zip(*m)])'
for v in f1 f2-f1; do
    t_bubble -s 128 -c 40 --value "$v" --tile -o "$T/t.pfm"
    r=$(pfm "$T/t.pfm" "$seam")
    [ "$r" = True ] && ok "--tile --value $v: seamless" || notok "--tile --value $v: seamless" "$r"
done
t_bubble -s 128 -c 40 --value f1 -o "$T/nt.pfm"
r=$(pfm "$T/nt.pfm" "$seam")
[ "$r" = False ] && ok "without --tile the seams show (the seam test can fail)" ||
    notok "without --tile the seams show"

# Cells: N distinct values when every cell is visible.
for n in 5 12; do
    t_bubble -s 256 -c "$n" --distribution poisson --value cell -o "$T/cell.pfm"
    r=$(pfm "$T/cell.pfm" 'len(set(x for r in m for x in r))')
    [ "$r" = "$n" ] && ok "-n $n --value cell: $n distinct values" || notok "-n $n cells" "$r values"
done

# 3D: slices differ, and --tile is periodic in z too.
t_bubble -s 64 -c 50 --dimension 3 --z 0.2 -o "$T/z1.pfm"
t_bubble -s 64 -c 50 --dimension 3 --z 0.3 -o "$T/z2.pfm"
t_bubble -s 64 -c 50 --dimension 3 --z 1.2 --tile -o "$T/z3.pfm"
t_bubble -s 64 -c 50 --dimension 3 --z 0.2 --tile -o "$T/z4.pfm"
if ! cmp -s "$T/z1.pfm" "$T/z2.pfm"; then ok "3D: --z chooses the slice"; else notok "3D: --z chooses the slice"; fi
check "3D --tile: slice z and z+1 are the same" cmp "$T/z3.pfm" "$T/z4.pfm"

# Points files.
printf '# two bubbles\n0.25 0.5\n0.75 0.5 2  # a bigger one\n\n' >"$T/two.txt"
t_bubble -s 64 --points "$T/two.txt" --value cell -o "$T/two.pfm"
r=$(pfm "$T/two.pfm" 'len(set(x for r in m for x in r))')
[ "$r" = 2 ] && ok "--points: two points, two cells" || notok "--points: two cells" "$r"
r=$(pfm "$T/two.pfm" 'sum(1 for r in m for x in r if x == m[32][63]) > sum(1 for r in m for x in r if x == m[32][0])')
[ "$r" = True ] && ok "--points: the radius column makes a bigger cell" || notok "radius column" "$r"
printf '0.2 0.2 0.2\n0.8 0.7 0.1 0.5\n0.5 0.5 0.9\n' >"$T/three.txt"
check "--points in 3D" t_bubble -s 32 --dimension 3 --points "$T/three.txt" -o "$T/3d.pfm"

# Bad input: one line naming the problem, status 1 or 2, nothing written.
printf '0.1 0.2\n0.3 zebra\n' >"$T/garbage.txt"
printf '0.1 0.2\nnan 0.4\n' >"$T/nan.txt"
printf '0.1 0.2\n\n0.5\n' >"$T/short.txt"
printf '# nothing\n\n' >"$T/empty.txt"
printf '0.1 0.2 -1\n' >"$T/negative.txt"
printf '0.1 0.2 1 2 3\n' >"$T/long.txt"
check_fails "-n 0 is a usage error" 2 t_bubble -c 0 -o "$T/bad.pfm"
check_fails "-n beyond 10000000 is a usage error" 2 t_bubble -c 10000001 -o "$T/bad.pfm"
check_fails "--metric minkowski:0.5 is a usage error" 2 t_bubble --metric minkowski:0.5 -o "$T/bad.pfm"
check_fails "--metric cosine is a usage error" 2 t_bubble --metric cosine -o "$T/bad.pfm"
check_fails "--size-spread 2 is a usage error" 2 t_bubble --size-spread 2 -o "$T/bad.pfm"
for f in garbage nan short empty negative long; do
    check_fails "points file with $f lines fails" 1 t_bubble -s 16 --points "$T/$f.txt" -o "$T/bad.pfm"
done
check_fails "a missing points file fails" 1 t_bubble -s 16 --points "$T/none.txt" -o "$T/bad.pfm"
t_bubble -s 16 --points "$T/garbage.txt" -o "$T/bad.pfm" 2>"$T/msg"
grep -q "garbage.txt:2: " "$T/msg" && ok "the message names file:line" || notok "file:line" "$(cat "$T/msg")"
t_bubble -s 16 --points "$T/short.txt" -o "$T/bad.pfm" 2>"$T/msg"
grep -q "short.txt:3: " "$T/msg" && ok "blank lines count in line numbers" || notok "line numbers" "$(cat "$T/msg")"
[ ! -e "$T/bad.pfm" ] && ok "nothing written on errors" || notok "nothing written on errors"

# Coincident points: FLANN's kd-tree visited every leaf for every query and the candidate
# tree split to its depth everywhere (10^4 copies of one point: over a minute; 10^4 within
# 10^-12 of one another: as long).  Each search answers within seconds, as the grid does.
python3 - "$T" <<'PY'
import random, sys
random.seed(7)
t = sys.argv[1]
same = ['0.5 0.5'] * 9000 + ['%.6f %.6f' % (random.random(), random.random()) for _ in range(200)]
same += ['0.25 0.75'] * 3000
random.shuffle(same)
open(t + '/same.txt', 'w').write('\n'.join(same) + '\n')
near = ['%.17g %.17g' % (0.5 + random.random() * 1e-12, 0.5 + random.random() * 1e-12)
        for _ in range(10000)]
open(t + '/near.txt', 'w').write('\n'.join(near) + '\n')
open(t + '/same3.txt', 'w').write('0.5 0.5 0.5\n' * 10000 + '0.2 0.3 0.4\n')
PY
for f in same near; do
    for s in kdtree grid; do
        for v in f2 cell; do
            timeout 20 t_bubble -s 48 --points "$T/$f.txt" --search $s --value $v -o "$T/$f-$s-$v.pfm"
            st=$?
            [ $st = 0 ] || notok "$f.txt --search $s --value $v within 20 s" "exit $st"
        done
    done
    cmp -s "$T/$f-kdtree-f2.pfm" "$T/$f-grid-f2.pfm" && cmp -s "$T/$f-kdtree-cell.pfm" "$T/$f-grid-cell.pfm" &&
        ok "$f.txt: the kd-tree answers within 20 s, as the grid does" ||
        notok "$f.txt: the kd-tree answers as the grid does"
done
timeout 20 t_bubble -s 32 --dimension 3 --points "$T/same3.txt" --search kdtree -o "$T/s3k.pfm" &&
    t_bubble -s 32 --dimension 3 --points "$T/same3.txt" --search brute -o "$T/s3b.pfm" &&
    cmp -s "$T/s3k.pfm" "$T/s3b.pfm" && ok "10^4 coincident points in 3D: the kd-tree as brute force" ||
    notok "10^4 coincident points in 3D: the kd-tree as brute force"
