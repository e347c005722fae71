/* noise_fold_template.c - a pixel row's coefficients at every entry of a folded grid's
 * table, written once.
 *
 * x86/noise_x86.c includes this file once per vector type after defining:
 *   FOLD_NAME  the row's function: FOLD_NAME(g, yr, P) writes P, and Q = P + ps
 *   FOLD_AT    the function for entries i..i + W - 1 (W = |V| / 4), from a fold_src
 *   FOLD_ATTR  their target attribute
 *   FOLD_V     the vector type (__m256, __m512), whose operators are its lanes'
 * These are the operations row_coeffs performs per slot, done once per entry.  The
 * table's planes go on past entry n (entry i is lattice column i mod n), so that
 * planar rows read up to 32 entries from a column's.
 */
FOLD_ATTR static inline __attribute__((always_inline)) void FOLD_AT(
    const struct fold_src *f, int i, FOLD_V *p, FOLD_V *q)
{
    const int ps = f->ps;
    FOLD_V x, y, c;
    memcpy(&x, f->T0 + i, sizeof x);
    memcpy(&y, f->T0 + ps + i, sizeof y);
    memcpy(&c, f->T0 + 2 * ps + i, sizeof c);
    *p = f->a0 * x;
    *q = f->a0 * (y * f->d0 + c);
    if (f->T1) {
        memcpy(&x, f->T1 + i, sizeof x);
        memcpy(&y, f->T1 + ps + i, sizeof y);
        memcpy(&c, f->T1 + 2 * ps + i, sizeof c);
        *p = *p + f->a1 * x;
        *q = *q + f->a1 * (y * f->d1 + c);
    }
}
FOLD_ATTR static void FOLD_NAME(const tex_noise_grid *g, const struct yrow *yr, float *P)
{
    enum { W = sizeof(FOLD_V) / sizeof(float) };
    struct fold_src f;
    fold_src_at(g, yr, &f);
    for (int i = 0; i < f.ps; i += W) {
        FOLD_V p, q;
        FOLD_AT(&f, i, &p, &q);
        memcpy(P + i, &p, sizeof p);
        memcpy(P + f.ps + i, &q, sizeof q);
    }
}

#undef FOLD_NAME
#undef FOLD_AT
#undef FOLD_ATTR
#undef FOLD_V
