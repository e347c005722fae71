/* noise_row_template.c - rows of a noise grid, written once.
 *
 * noise.c (the portable rows) and x86/noise_x86.c (AVX2, AVX-512) include this
 * file once per instruction set, as FFmpeg does with its *_template.c files,
 * after defining:
 *   GRID_ROW     the function's name
 *   GRID_ATTR    its target attribute, and static if the function is the file's own
 *   GRID_COEFFS  the kernel that blends two lattice rows into P and Q
 *   GRID_PIXELS  the kernel that turns P and Q into pixels (with op and its constants rk)
 *   GRID_LUT_ROW (optional) the whole rows of a folded or paired grid with a table
 * The result is a real function, visible to debuggers and profilers.  It makes
 * rows y.. y + rows - 1 (rows at most FOLD_ROWS) into out[0..rows-1].
 */
GRID_ATTR void GRID_ROW(const tex_noise_grid *g, int y, int rows, int op, struct row_k rk,
                        float *const *out)
{
    float C[FOLD_ROWS][2 * ROW_NS], L[6][ROW_NS];
    struct yrow yr[FOLD_ROWS];
    struct cache_entry *e;

    for (int r = 0; r < rows; r++)
        tex_noise_yrow_at(g, y + r, &yr[r]);
#ifdef GRID_LUT_ROW
    if (g->folded || (g->paired && g->lut)) {
        GRID_LUT_ROW(g, yr, rows, out, op, rk);
        return;
    }
#endif
    /* Rows together where the whole row's coefficients fit, else one by one in chunks of
     * columns, so that the coefficients stay on the stack and in L1. */
    int n = rows > 1 && g->nslots + 16 <= ROW_NS ? rows : 1, chunk = n > 1 ? g->w : ROW_CHUNK;
    e = tex_noise_cache_take(g);
    for (int r0 = 0; r0 < rows; r0 += n)
        for (int x0 = 0; x0 < g->w; x0 += chunk) {
            int x1 = x0 + chunk < g->w ? x0 + chunk : g->w;
            int s0 = g->slot[x0], s1 = g->slot[x1 - 1] + 2;
            struct rowset rs;
            for (int r = 0; r < n; r++) {
                const struct yrow *q = &yr[r0 + r];
                const float *L0[3], *L1[3], *l0 = NULL, *l1 = NULL;
                if (e)
                    tex_noise_cache_rows(g, e, q->j, q->two, &l0, &l1);
                for (int k = 0; k < 3; k++) {
                    L0[k] = e ? l0 + k * (size_t)g->stride + s0 : L[k];
                    L1[k] = !q->two ? NULL : e ? l1 + k * (size_t)g->stride + s0 : L[3 + k];
                }
                if (!e) {
                    tex_noise_lattice_row(g, q->j, s0, s1, L[0], L[1], L[2]);
                    if (q->two)
                        tex_noise_lattice_row(g, q->j + 1, s0, s1, L[3], L[4], L[5]);
                }
                GRID_COEFFS(s1 - s0, q->wy, q->dy, L0, q->two ? L1 : NULL, C[r], C[r] + ROW_NS);
                rs.C[r] = C[r];
                rs.out[r] = out[r0 + r];
            }
            GRID_PIXELS(g, rs, s0, x0, x1, n, op, rk);
        }
    if (e)
        __atomic_store_n(&e->busy, 0, __ATOMIC_RELEASE);
}

#undef GRID_ROW
#undef GRID_ATTR
#undef GRID_COEFFS
#undef GRID_PIXELS
#undef GRID_LUT_ROW
