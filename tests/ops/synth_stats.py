#!/usr/bin/env python3
"""synth_stats.py - texture statistics for tests/ops/synth.sh (pure Python, no numpy).

  synth_stats.py dist SAMPLE.pfm MAP.pfm...
                                           distances of each MAP's statistics from
                                           SAMPLE's: "hist spectrum orient" (see
                                           below), a line for each MAP
  synth_stats.py crops SAMPLE.pfm W H C SEED OUT.pfm
                                           the baseline: random C x C crops of the sample
                                           tiled into a W x H map
  synth_stats.py period MAP.pfm P          autocorrelation of the luma at lags P and P/2
                                           along x and along y: "ax ax2 ay ay2"
  synth_stats.py peak MAP.pfm LO HI        the lags in LO..HI of highest autocorrelation
                                           along x and along y: "lagx lagy"
  synth_stats.py seam MAP.pfm              mean |step| across the wrap-around seams, and
                                           the largest mean |step| of an inner column/row
  synth_stats.py corr A.pfm B.pfm          correlation of the two maps' lumas
  synth_stats.py same_outside SAMPLE MASK OUT
                                           1 if OUT equals SAMPLE wherever MASK <= 0.5

Distances: hist, the L1 distance of 32-bin per-channel histograms over [0,1], averaged
over channels (0..2); spectrum, the mean |log10 P_map - log10 P_sample| of the radially
averaged power spectra of the lumas (16 bands of frequency in cycles per pixel, 0..0.5,
DC left out; a DFT of every row and column, so maps of any size compare); orient, the
L1 distance of 16-bin gradient-orientation histograms weighted by the gradient's length
(central differences of the luma, orientation modulo pi).
"""
import cmath
import math
import operator
import random
import struct
import sys


def read_pfm(path):
    d = open(path, 'rb').read()
    head, rest = d.split(b'\n', 1)
    dims, rest = rest.split(b'\n', 1)
    scale, data = rest.split(b'\n', 1)
    nc = 3 if head.strip() == b'PF' else 1
    w, h = map(int, dims.split())
    v = struct.unpack(('<' if float(scale) < 0 else '>') + '%df' % (w * h * nc), data[:4 * w * h * nc])
    rows = [v[(h - 1 - y) * w * nc:(h - y) * w * nc] for y in range(h)]  # bottom row first
    return w, h, nc, rows


def write_pfm(path, w, h, nc, rows):
    with open(path, 'wb') as f:
        f.write(b'%s\n%d %d\n-1.0\n' % (b'PF' if nc == 3 else b'Pf', w, h))
        for y in range(h - 1, -1, -1):
            f.write(struct.pack('<%df' % (w * nc), *rows[y]))


def luma(m):
    w, h, nc, rows = m
    if nc == 1:
        return [list(r) for r in rows]
    return [[0.2126 * r[3 * x] + 0.7152 * r[3 * x + 1] + 0.0722 * r[3 * x + 2] for x in range(w)]
            for r in rows]


def hist(m, c, bins=32):
    w, h, nc, rows = m
    hs = [0] * bins
    for r in rows:
        for x in range(w):
            v = r[x * nc + c]
            hs[min(bins - 1, max(0, int(v * bins)))] += 1
    return [a / (w * h) for a in hs]


def dft(a):
    n = len(a)
    return [sum(a[t] * cmath.exp(-2j * math.pi * k * t / n) for t in range(n)) for k in range(n)]


def fft(a):
    n = len(a)
    if n & (n - 1):
        return dft(a)
    if n == 1:
        return list(a)
    e, o = fft(a[0::2]), fft(a[1::2])
    tw = [cmath.exp(-2j * math.pi * k / n) * o[k] for k in range(n // 2)]
    return [e[k] + tw[k] for k in range(n // 2)] + [e[k] - tw[k] for k in range(n // 2)]


def spectrum(m, bands=16):
    L = luma(m)
    h, w = len(L), len(L[0])
    mean = sum(map(sum, L)) / (w * h)
    rows = [fft([v - mean for v in r]) for r in L]
    cols = [fft([rows[y][x] for y in range(h)]) for x in range(w)]
    p, n = [0.0] * bands, [0] * bands
    for x in range(w):
        fx = min(x, w - x) / w
        for y in range(h):
            fy = min(y, h - y) / h
            f = math.hypot(fx, fy)
            if f == 0 or f >= 0.5:
                continue
            b = int(f * 2 * bands)
            p[b] += abs(cols[x][y]) ** 2 / (w * h)
            n[b] += 1
    return [math.log10(p[b] / n[b] + 1e-12) if n[b] else 0 for b in range(bands)]


def orient(m, bins=16):
    L = luma(m)
    h, w = len(L), len(L[0])
    hs = [0.0] * bins
    for y in range(1, h - 1):
        for x in range(1, w - 1):
            gx = L[y][x + 1] - L[y][x - 1]
            gy = L[y + 1][x] - L[y - 1][x]
            g = math.hypot(gx, gy)
            if g > 0:
                a = math.atan2(gy, gx) % math.pi
                hs[min(bins - 1, int(a / math.pi * bins))] += g
    s = sum(hs) or 1
    return [a / s for a in hs]


def l1(a, b):
    return sum(abs(x - y) for x, y in zip(a, b))


def figures(m, nc):
    return [hist(m, c) for c in range(nc)], spectrum(m), orient(m)


def dist(sf, m):
    (sh, ss, so), nc = sf, len(sf[0])
    mh, ms, mo = figures(m, nc)
    dh = sum(l1(a, b) for a, b in zip(sh, mh)) / nc
    ds = sum(abs(a - b) for a, b in zip(ss, ms)) / len(ss)
    return dh, ds, l1(so, mo)


def crops(sample, w, h, c, seed):
    sw, sh, nc, rows = sample
    rnd = random.Random(seed)
    out = [[0.0] * (w * nc) for _ in range(h)]
    for by in range(0, h, c):
        for bx in range(0, w, c):
            ox, oy = rnd.randrange(sw - c + 1), rnd.randrange(sh - c + 1)
            for y in range(by, min(by + c, h)):
                for x in range(bx, min(bx + c, w)):
                    for k in range(nc):
                        out[y][x * nc + k] = rows[oy + y - by][(ox + x - bx) * nc + k]
    return out


def centred(L):
    h, w = len(L), len(L[0])
    mean = sum(map(sum, L)) / (w * h)
    C = [[v - mean for v in r] for r in L]
    return C, sum(sum(map(operator.mul, r, r)) for r in C) / (w * h)


def autocorr(L, dx, dy, cv=None):
    """The circular autocorrelation of L at lag (dx, dy), one of them 0 (rows or columns
    products summed by map, not by a Python loop per pixel)."""
    C, var = cv or centred(L)
    h, w = len(C), len(C[0])
    if dy == 0:
        s = sum(sum(map(operator.mul, r, r[dx % w:] + r[:dx % w])) for r in C)
    else:
        s = sum(sum(map(operator.mul, C[y], C[(y + dy) % h])) for y in range(h))
    return s / (w * h) / var


def main():
    cmd, a = sys.argv[1], sys.argv[2:]
    if cmd == 'dist':
        s = read_pfm(a[0])
        sf = figures(s, min(s[2], 3))
        for p in a[1:]:
            print('%.4f %.4f %.4f' % dist(sf, read_pfm(p)))
    elif cmd == 'crops':
        s = read_pfm(a[0])
        w, h, c, seed = map(int, a[1:5])
        write_pfm(a[5], w, h, s[2], crops(s, w, h, c, seed))
    elif cmd == 'period':
        L, p = luma(read_pfm(a[0])), int(a[1])
        cv = centred(L)
        print('%.3f %.3f %.3f %.3f' % (autocorr(L, p, 0, cv), autocorr(L, p // 2, 0, cv),
                                       autocorr(L, 0, p, cv), autocorr(L, 0, p // 2, cv)))
    elif cmd == 'peak':
        L, lo, hi = luma(read_pfm(a[0])), int(a[1]), int(a[2])
        cv = centred(L)
        lx = max(range(lo, hi + 1), key=lambda t: autocorr(L, t, 0, cv))
        ly = max(range(lo, hi + 1), key=lambda t: autocorr(L, 0, t, cv))
        print(lx, ly)
    elif cmd == 'seam':
        L = luma(read_pfm(a[0]))
        h, w = len(L), len(L[0])
        col = lambda x: sum(abs(L[y][(x + 1) % w] - L[y][x]) for y in range(h)) / h
        row = lambda y: sum(abs(L[(y + 1) % h][x] - L[y][x]) for x in range(w)) / w
        seam = max(col(w - 1), row(h - 1))
        inner = max(max(col(x) for x in range(w - 1)), max(row(y) for y in range(h - 1)))
        print('%.4f %.4f' % (seam, inner))
    elif cmd == 'corr':
        A, B = luma(read_pfm(a[0])), luma(read_pfm(a[1]))
        va = [v for r in A for v in r]
        vb = [v for r in B for v in r]
        ma, mb = sum(va) / len(va), sum(vb) / len(vb)
        cov = sum((x - ma) * (y - mb) for x, y in zip(va, vb))
        sa = math.sqrt(sum((x - ma) ** 2 for x in va))
        sb = math.sqrt(sum((y - mb) ** 2 for y in vb))
        print('%.3f' % (cov / (sa * sb)))
    elif cmd == 'same_outside':
        s, k, o = read_pfm(a[0]), read_pfm(a[1]), read_pfm(a[2])
        w, h, nc, rows = s
        ok = all(o[3][y][x * nc + c] == rows[y][x * nc + c] for y in range(h) for x in range(w)
                 if k[3][y][x * k[2]] <= 0.5 for c in range(nc))
        print(1 if ok else 0)


main()
