/* noise_row_template.c - rows of a noise grid, written once.
 *
 * noise.c includes this file once per instruction set, as FFmpeg does with
 * its *_template.c files, after defining:
 *   GRID_ROW     the function's name
 *   GRID_ATTR    its target attribute (empty for the portable path)
 *   GRID_COEFFS  the kernel that blends two lattice rows into P and Q
 *   GRID_PIXELS  the kernel that turns P and Q into pixels (with op and its constants rk)
 *   GRID_LUT_ROW (optional) the whole rows of a folded or paired grid with a table
 * The result is a real function, visible to debuggers and profilers.  It makes
 * rows y.. y + rows - 1 (rows at most FOLD_ROWS) into out[0..rows-1].
 */
GRID_ATTR static void GRID_ROW(const tex_noise_grid *g, int y, int rows, int op, struct row_k rk,
                               float *const *out)
{
    enum { CHUNK = 1024, NS = 2 * CHUNK + 24 };
    float P[NS], Q[NS], L[6][NS];
    struct yrow yr[FOLD_ROWS];
    struct cache_entry *e;

    for (int r = 0; r < rows; r++)
        yrow_at(g, y + r, &yr[r]);
#ifdef GRID_LUT_ROW
    if (g->folded || (g->paired && g->lut)) {
        GRID_LUT_ROW(g, yr, rows, out, op, rk);
        return;
    }
#endif
    e = cache_take(g);
    for (int r = 0; r < rows; r++) {
        const float *r0 = NULL, *r1 = NULL, *wy = yr[r].wy, *dy = yr[r].dy;
        int64_t j = yr[r].j;
        int two = yr[r].two;
        if (e)
            cache_rows(g, e, j, two, &r0, &r1);
        for (int x0 = 0; x0 < g->w; x0 += CHUNK) {
            int x1 = x0 + CHUNK < g->w ? x0 + CHUNK : g->w;
            int s0 = g->slot[x0], s1 = g->slot[x1 - 1] + 2;
            const float *L0[3], *L1[3];
            if (e) {
                for (int k = 0; k < 3; k++) {
                    L0[k] = r0 + k * (size_t)g->stride + s0;
                    L1[k] = two ? r1 + k * (size_t)g->stride + s0 : NULL;
                }
            } else {
                lattice_row(g, j, s0, s1, L[0], L[1], L[2]);
                if (two)
                    lattice_row(g, j + 1, s0, s1, L[3], L[4], L[5]);
                for (int k = 0; k < 3; k++) {
                    L0[k] = L[k];
                    L1[k] = L[3 + k];
                }
            }
            GRID_COEFFS(s1 - s0, wy, dy, L0, two ? L1 : NULL, P, Q);
            GRID_PIXELS(g, P, Q, s0, out[r], x0, x1, op, rk);
        }
    }
    if (e)
        __atomic_store_n(&e->busy, 0, __ATOMIC_RELEASE);
}

#undef GRID_ROW
#undef GRID_ATTR
#undef GRID_COEFFS
#undef GRID_PIXELS
#undef GRID_LUT_ROW
