/* noise_points_template.c - 3D noise at many points, W at a time, written once.
 *
 * x86/noise_points_x86.c includes this file once per width after defining:
 *   POINTS_NAME    the function: POINTS_NAME(t, period, a, f, c, n, out) makes the
 *                  first n - n % W points and returns how many
 *   POINTS_COORDS  the name of its helper that loads points i.. i + W - 1: a + f (u,
 *                  v, w) (w NULL: 0) as tex_noise_points_at makes them, or (u, v, w)
 *                  themselves when a is NULL
 *   POINTS_ATTR    their target attribute
 *   POINTS_STATIC  static if the function is the file's own, else empty
 *   POINTS_W       the points at a time
 *   POINTS_VD      the vector of doubles (__m256d, __m512d: two make W), whose
 *                  operators are its lanes' (a scalar taken as a vector of it)
 *   POINTS_LOADU   its unaligned load
 *   POINTS_LANES   the struct of the lanes' fractions, weights and hashes
 *   POINTS_SETUP   a statement run first (what the hashes need)
 *   POINTS_HASH(L, p)   the lanes of the points p into *L; 0 for a cell beyond 2^30
 *   POINTS_SUM(L, out)  the eight corners' sum of the lanes *L into out
 * The hashes of the next W points are made before these W points' corners are summed,
 * so that their dependent gathers are under way meanwhile.  Points the kernel cannot
 * take (cells beyond 2^30) go to tex_noise3_point_at.
 */
POINTS_ATTR static inline __attribute__((always_inline)) void POINTS_COORDS(
    const double *a, double f, const double *const c[3], int i, POINTS_VD p[3][2])
{
    enum { W = sizeof(POINTS_VD) / sizeof(double) };
    for (int k = 0; k < 3; k++)
        for (int h = 0; h < 2; h++) {
            POINTS_VD x = {0};
            if (c[k])
                x = POINTS_LOADU(c[k] + i + W * h);
            p[k][h] = x;
            if (a)
                p[k][h] = a[k] + f * x;
        }
}

POINTS_ATTR POINTS_STATIC int POINTS_NAME(const tex_noise_table *t, int period, const double *a,
                                          double f, const double *const c[3], int n, float *out)
{
    struct POINTS_LANES L[2];
    int ok[2], m = n / POINTS_W;
    POINTS_VD p[3][2];
    POINTS_SETUP;
    if (m == 0)
        return 0;
    POINTS_COORDS(a, f, c, 0, p);
    ok[0] = POINTS_HASH(&L[0], p);
    for (int k = 0; k < m; k++) {
        if (k + 1 < m) {
            POINTS_COORDS(a, f, c, POINTS_W * (k + 1), p);
            ok[(k + 1) & 1] = POINTS_HASH(&L[(k + 1) & 1], p);
        }
        if (ok[k & 1])
            POINTS_SUM(&L[k & 1], out + POINTS_W * k);
        else
            for (int i = POINTS_W * k; i < POINTS_W * k + POINTS_W; i++)
                out[i] = tex_noise3_point_at(t, period, a, f, c, i);
    }
    return POINTS_W * m;
}

#undef POINTS_NAME
#undef POINTS_COORDS
#undef POINTS_ATTR
#undef POINTS_STATIC
#undef POINTS_W
#undef POINTS_VD
#undef POINTS_LOADU
#undef POINTS_LANES
#undef POINTS_SETUP
#undef POINTS_HASH
#undef POINTS_SUM
