/* footprint_template.c - a packet's footprints (footprint.c's) as one body for every width
 *
 * Included by packet_x86.c once for AVX-512's eight lanes and once for AVX2's four, with
 * FP_TARGET the target attribute, FP_TANGENTS, FP_FOOTPRINTS and FP_SOLID_FOOTPRINTS the
 * functions' names, vd the vector of doubles, vmask the lanes' mask, and V_* the operations
 * in that width (packet_x86.c defines them: each the intrinsic the width has).  The same C,
 * so the same operations in the same order at both widths, the scalar path's.  Not compiled
 * alone.
 *
 * V_LD(a) and V_ST(a, v) load and store row a's lanes in (of mask in, from lane i on; 0 in the
 * others); V_GT_ELSE(a, lo) is a > lo ? a : lo; V_LT_BITS(a, b) the lanes where a < b as bits.
 * The template undefines them all at its end.
 */

/* the lanes in of row a from lane i on; LDG: of a row the lanes may share (struct frames) */
#define LDG(a) (fr->shared ? V_SET1((a)[0]) : V_LD(a))

/* footprint_tangents of the lanes in of fr from i on, operation for operation: t1, t2 (x, y,
 * z), l2 and c; the lanes seen head-on (no tangent from the ray) as bits */
FP_TARGET static inline __attribute__((always_inline)) unsigned
FP_TANGENTS(const struct frames *fr, int i, vmask in, vd t1[3], vd t2[3], vd *l2, vd *c)
{
    vd d[3], nn[3];
    for (int k = 0; k < 3; k++)
        d[k] = V_LD(fr->d[k]), nn[k] = V_LD(fr->nn[k]);
    vd dn = V_DOT(d[0], d[1], d[2], nn[0], nn[1], nn[2]), cosv = V_ABS(dn), ndn = V_NEG(dn);
    for (int k = 0; k < 3; k++)
        t1[k] = V_ADD(d[k], V_MUL(nn[k], ndn));
    *l2 = V_DOT(t1[0], t1[1], t1[2], t1[0], t1[1], t1[2]);
    for (int k = 0; k < 3; k++) /* N x t1 */
        t2[k] = V_SUB(V_MUL(nn[(k + 1) % 3], t1[(k + 2) % 3]),
                      V_MUL(nn[(k + 2) % 3], t1[(k + 1) % 3]));
    *c = V_GT_ELSE(cosv, V_SET1(0.02));
    return V_LT_BITS(*l2, V_SET1(1e-18));
}

/* tex_footprint_width2 of the n points from i on (footprint_tangents,
 * placed_derivatives and its end, operation for operation) into fw2[i...], and where bump,
 * the frames' bump members; returns the lanes seen head-on, which the scalar path takes. */
FP_TARGET unsigned FP_FOOTPRINTS(struct frames *fr, int i, int n, int bump, double *fw2)
{
    vmask in = V_IN(n);
    vd t1[3], t2[3], l2, c;
    unsigned headon = FP_TANGENTS(fr, i, in, t1, t2, &l2, &c);
    vd gu[3] = {LDG(fr->gu[0]), LDG(fr->gu[1]), LDG(fr->gu[2])};
    vd gv[3] = {LDG(fr->gv[0]), LDG(fr->gv[1]), LDG(fr->gv[2])};
    vd su = LDG(fr->su), sv = LDG(fr->sv), w = V_LD(fr->w);
    vd du0 = V_MUL(V_DOT(gu[0], gu[1], gu[2], t1[0], t1[1], t1[2]), su);
    vd dv0 = V_MUL(V_DOT(gv[0], gv[1], gv[2], t1[0], t1[1], t1[2]), sv);
    vd du1 = V_MUL(V_DOT(gu[0], gu[1], gu[2], t2[0], t2[1], t2[2]), su);
    vd dv1 = V_MUL(V_DOT(gv[0], gv[1], gv[2], t2[0], t2[1], t2[2]), sv);
    vd c2 = V_MUL(c, c);
    vd l1 = V_ADD(V_MUL(du0, du0), V_MUL(dv0, dv0));
    vd m2 = V_MUL(V_ADD(V_MUL(du1, du1), V_MUL(dv1, dv1)), c2);
    vd r = V_MUL(V_MAX(l1, m2), V_MUL(w, w)); /* l1 > m2 ? l1 : m2 */
    V_ST(fw2, V_DIV(r, V_MUL(l2, c2)));
    if (bump) { /* footprint_unit's tangents, placed_derivatives along them */
        vd s = V_DIV(V_SET1(1), V_SQRT(l2));
        vd e1[3] = {V_MUL(t1[0], s), V_MUL(t1[1], s), V_MUL(t1[2], s)};
        vd e2[3] = {V_MUL(t2[0], s), V_MUL(t2[1], s), V_MUL(t2[2], s)};
        vd dd[4] = {V_MUL(V_DOT(gu[0], gu[1], gu[2], e1[0], e1[1], e1[2]), su),
                    V_MUL(V_DOT(gv[0], gv[1], gv[2], e1[0], e1[1], e1[2]), sv),
                    V_MUL(V_DOT(gu[0], gu[1], gu[2], e2[0], e2[1], e2[2]), su),
                    V_MUL(V_DOT(gv[0], gv[1], gv[2], e2[0], e2[1], e2[2]), sv)};
        for (int c = 0; c < 3; c++) {
            V_ST(fr->e1[c], e1[c]);
            V_ST(fr->e2[c], e2[c]);
        }
        for (int c = 0; c < 4; c++)
            V_ST(c & 1 ? fr->dv[c / 2] : fr->du[c / 2], dd[c]);
    }
    return headon & ((1u << n) - 1);
}

/* The footprint widths of the n band-limited solid points from i on, as
 * sqrt(tex_solid_width2) makes them under an affine mapping (footprint_tangents, the three
 * gradients' derivatives along t1 and t2, operation for operation), into fw[i...]; returns
 * the lanes seen head-on, which the scalar path takes. */
FP_TARGET unsigned FP_SOLID_FOOTPRINTS(const struct frames *fr, int i, int n, double *fw)
{
    vmask in = V_IN(n);
    vd t1[3], t2[3], l2, c;
    unsigned headon = FP_TANGENTS(fr, i, in, t1, t2, &l2, &c);
    const double(*g[3])[CHUNK] = {fr->gu, fr->gv, fr->gw};
    vd sc[3] = {LDG(fr->su), LDG(fr->sv), V_SET1(1)}, l1 = V_ZERO(), m2 = V_ZERO();
    vd w = V_LD(fr->w);
    for (int k = 0; k < 3; k++) { /* l1 += a a, m2 += b b, as tex_solid_width2 sums them */
        vd gx = LDG(g[k][0]), gy = LDG(g[k][1]), gz = LDG(g[k][2]);
        vd a = V_MUL(V_DOT(gx, gy, gz, t1[0], t1[1], t1[2]), sc[k]);
        vd b = V_MUL(V_DOT(gx, gy, gz, t2[0], t2[1], t2[2]), sc[k]);
        l1 = V_ADD(l1, V_MUL(a, a));
        m2 = V_ADD(m2, V_MUL(b, b));
    }
    vd r = V_DIV(V_MUL(V_SQRT(V_MUL(l1, m2)), V_MUL(w, w)), V_MUL(c, l2));
    V_ST(fw, V_SQRT(r));
    return headon & ((1u << n) - 1);
}

#undef LDG
/* what the includer gave: the next inclusion gives its own */
#undef FP_TARGET
#undef FP_TANGENTS
#undef FP_FOOTPRINTS
#undef FP_SOLID_FOOTPRINTS
#undef vd
#undef vmask
#undef V_IN
#undef V_LD
#undef V_ST
#undef V_SET1
#undef V_ZERO
#undef V_ADD
#undef V_SUB
#undef V_MUL
#undef V_DIV
#undef V_SQRT
#undef V_MAX
#undef V_DOT
#undef V_ABS
#undef V_NEG
#undef V_GT_ELSE
#undef V_LT_BITS
