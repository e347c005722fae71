/* noise_apply_template.c - a grid row's operation on a vector of pixels, written once.
 *
 * x86/noise_x86.c includes this file once per vector type, as FFmpeg does with
 * its *_template.c files, after defining:
 *   APPLY_NAME     the function's name
 *   APPLY_ATTR     its target attribute
 *   APPLY_V        the vector type (__m256, __m512), whose operators are its lanes'
 *   APPLY_MIN, APPLY_MAX, APPLY_ABS   its intrinsics (clamps are max, then min)
 *   APPLY_ROWWISE  1: the operations without a state go row by row
 * APPLY_NAME(op, r, out, x, rows, rk) performs apply_op (../noise_grid.h) on the
 * W = |V| / 4 pixels at x of each of the rows at out, their noise r[i], in its
 * order of operations.  The multifractal operations load every row's sum and
 * state before any row's stores; the others go row by row where APPLY_ROWWISE
 * (AVX-512's, where that is faster; AVX2's is slower so).
 */
APPLY_ATTR static inline __attribute__((always_inline)) void APPLY_NAME(
    const int op, const APPLY_V *r, float *const *out, int x, const int rows, struct row_k rk)
{
    const APPLY_V zero = {0}, one = zero + 1.0f;
    const int first = op == TEX_ROW_RIDGED_FIRST || op == TEX_ROW_HYBRID_FIRST;
    const int last = op == TEX_ROW_RIDGED_LAST || op == TEX_ROW_HYBRID_LAST;
    float *sp[FOLD_ROWS]; /* the multifractal state */
    APPLY_V v[FOLD_ROWS], s[FOLD_ROWS], st[FOLD_ROWS];
    const int step = APPLY_ROWWISE && op < TEX_ROW_RIDGED_FIRST ? 1 : rows;
    for (int i0 = 0; i0 < rows; i0 += step) {
        #pragma GCC unroll 2
        for (int i = i0; i < i0 + step; i++) {
            sp[i] = state_at(out[i] + x, rk);
            if (op >= TEX_ROW_ADD && !first)
                memcpy(&v[i], out[i] + x, sizeof v[i]);
            if (op >= TEX_ROW_RIDGED_FIRST && !first)
                memcpy(&st[i], sp[i], sizeof st[i]);
        }
        #pragma GCC unroll 2
        for (int i = i0; i < i0 + step; i++) {
            switch (op) {
            case TEX_ROW_SET: v[i] = r[i]; break;
            case TEX_ROW_MUL: v[i] = rk.a * r[i]; break;
            case TEX_ROW_MUL_ABS: v[i] = rk.a * APPLY_ABS(r[i]); break;
            case TEX_ROW_UNIT: v[i] = APPLY_MIN(APPLY_MAX(0.5f + 0.5f * r[i], zero), one); break;
            case TEX_ROW_ADD: v[i] = v[i] + rk.a * r[i]; break;
            case TEX_ROW_ADD_ABS: v[i] = v[i] + rk.a * APPLY_ABS(r[i]); break;
            case TEX_ROW_ADD_UNIT:
                v[i] = APPLY_MIN(APPLY_MAX(0.5f + 0.5f * ((v[i] + rk.a * r[i]) * rk.b), zero), one);
                break;
            case TEX_ROW_ADD_ABS_CLAMP:
                v[i] = APPLY_MIN(APPLY_MAX((v[i] + rk.a * APPLY_ABS(r[i])) * rk.b, zero), one);
                break;
            case TEX_ROW_RIDGED_FIRST:
                s[i] = rk.b - APPLY_ABS(r[i]);
                v[i] = s[i] = s[i] * s[i];
                break;
            case TEX_ROW_RIDGED:
            case TEX_ROW_RIDGED_LAST:
                s[i] = rk.b - APPLY_ABS(r[i]);
                s[i] = APPLY_MIN(st[i] * rk.c, one) * (s[i] * s[i]);
                v[i] = v[i] + s[i] * rk.a;
                break;
            case TEX_ROW_HYBRID_FIRST: v[i] = s[i] = (r[i] + rk.b) * rk.a; break;
            default: /* TEX_ROW_HYBRID, TEX_ROW_HYBRID_LAST */
                s[i] = APPLY_MIN(st[i], one) * ((r[i] + rk.b) * rk.a);
                v[i] = v[i] + s[i];
                break;
            }
            if (last)
                v[i] = APPLY_MIN(APPLY_MAX((v[i] - rk.lo) * rk.inv, zero), one);
        }
        #pragma GCC unroll 2
        for (int i = i0; i < i0 + step; i++) {
            memcpy(out[i] + x, &v[i], sizeof v[i]);
            if (op >= TEX_ROW_RIDGED_FIRST && !last)
                memcpy(sp[i], &s[i], sizeof s[i]);
        }
    }
}

#undef APPLY_NAME
#undef APPLY_ATTR
#undef APPLY_V
#undef APPLY_MIN
#undef APPLY_MAX
#undef APPLY_ABS
#undef APPLY_ROWWISE
