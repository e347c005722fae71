/* sample_template.c - the sampler's lookup (tex_sample) as one body for every SIMD level
 *
 * Included by transform.c for the portable path and by x86/sample_x86.c for AVX2, with
 * SAMPLE_FN the function's name and SAMPLE_TARGET its target attribute (empty, or
 * the AVX2 target): the same C, so the same double and float operations in the same order (no
 * contraction: -ffp-contract=off), where AVX2's code rounds (floor, ceil) in one
 * instruction and so costs less.  Not compiled alone.
 */
/* Pixel (ix,iy) through the edge rule: a pointer into the map or to bg. */
SAMPLE_TARGET static inline const float *fetch(const struct tex_sampler *s, long ix, long iy)
{
    long x = tex_edge_index(ix, s->m->w, s->edge), y = tex_edge_index(iy, s->rows, s->edge);

    if (x < 0 || y < 0)
        return s->bg;
    y -= s->row0; /* counted from the band's first row, modulo the map's: a band may wrap */
    y = y < 0 ? y + s->rows : y >= s->rows ? y - s->rows : y;
    if (y >= s->m->h) /* a band short of the rows it needs: its caller's error */
        return s->bg;
    return tex_map_px(s->m, (int)x, (int)y);
}

/* Huge or non-finite coordinates (from a wild warp) are pinned far outside
 * the map, where the edge rule still gives an answer. */
SAMPLE_TARGET static inline double tame(double x)
{
    return x > -1e9 && x < 1e9 ? x : (x > 0 ? 1e9 : -1e9);
}

/* inlined into tex_sample's tap loop: a call per tap cost more than the sums */
SAMPLE_TARGET static inline __attribute__((always_inline)) void bilinear(
    const struct tex_sampler *s, double x, double y, float *out)
{
    int nc = s->m->nc;
    double fx = tame(x) - 0.5, fy = tame(y) - 0.5, x0 = floor(fx), y0 = floor(fy);
    float tx = (float)(fx - x0), ty = (float)(fy - y0);
    long ix = (long)x0, iy = (long)y0, ry = iy - s->row0;
    const float *p00, *p10, *p01, *p11;

    if (ix >= 0 && ix + 1 < s->m->w && iy >= 0 && iy + 1 < s->rows && ry >= 0 &&
        ry + 1 < s->m->h) { /* inside: the four pixels fetch() would give, without the edge rule */
        p00 = tex_map_px(s->m, (int)ix, (int)ry);
        p10 = p00 + nc;
        p01 = p00 + (size_t)s->m->w * nc;
        p11 = p01 + nc;
    } else {
        p00 = fetch(s, ix, iy);
        p10 = fetch(s, ix + 1, iy);
        p01 = fetch(s, ix, iy + 1);
        p11 = fetch(s, ix + 1, iy + 1);
    }

    if (nc == 1) { /* a grey map, the warp's usual, without the loop: the same sums */
        float a = p00[0] + (p10[0] - p00[0]) * tx, b = p01[0] + (p11[0] - p01[0]) * tx;
        out[0] = a + (b - a) * ty;
        return;
    }
    for (int c = 0; c < nc; c++) {
        float a = p00[c] + (p10[c] - p00[c]) * tx, b = p01[c] + (p11[c] - p01[c]) * tx;
        out[c] = a + (b - a) * ty;
    }
}

/* Lookups along one axis: about one per source pixel the output pixel spans,
 * so each bilinear tap covers its share; one (plain bilinear) at 1:1 and when
 * magnifying, which keeps whole-pixel lookups exact. */
SAMPLE_TARGET static inline int taps(const double d[2], int maxtaps)
{
    double n;

    /* |a| + |b| <= 1 bounds hypot() by 1 + a few ulp, far below the 1e-6
     * that makes a second tap: one tap, as hypot() would give, at less cost. */
    if (fabs(d[0]) + fabs(d[1]) <= 1.0)
        return 1;
    /* sqrt of the squares is within a few ulp of hypot(), which costs four times more:
     * its ceiling is hypot()'s unless the length lies within 1e-9 of a whole number (or
     * overflows), where hypot() decides */
    n = sqrt(d[0] * d[0] + d[1] * d[1]) - 1e-6;
    if (!(n < 1e6 && n - floor(n) > 1e-9 && ceil(n) - n > 1e-9))
        n = hypot(d[0], d[1]) - 1e-6;
    n = ceil(n);
    return n < 1 ? 1 : n > maxtaps ? maxtaps : (int)n;
}

/* Tap i of n's offset, (i + 0.5) / n - 0.5: two taps, the usual many, at -1/4 and 1/4
 * (exactly the quotients) without a division */
SAMPLE_TARGET static inline double offset(int i, int n)
{
    return n == 2 ? (i ? 0.25 : -0.25) : (i + 0.5) / n - 0.5;
}

SAMPLE_TARGET void SAMPLE_FN(const struct tex_sampler *s, double x, double y, const double du[2],
                             const double dv[2], float *out)
{
    int nc = s->m->nc, nu, nv, maxt = s->maxtaps > 0 ? s->maxtaps : 32;
    float acc[4] = {0, 0, 0, 0}, v[4];

    if (s->nearest) {
        const float *p = fetch(s, (long)floor(tame(x)), (long)floor(tame(y)));
        memcpy(out, p, nc * sizeof *out);
        return;
    }
    nu = taps(du, maxt);
    nv = taps(dv, maxt);
    if (nu == 1 && nv == 1) {
        bilinear(s, x, y, out);
        return;
    }
    double as[64]; /* the taps' offsets along u, divided once rather than per row */
    int once = nu <= 64;
    for (int i = 0; once && i < nu; i++)
        as[i] = offset(i, nu);
    for (int j = 0; j < nv; j++) {
        double b = offset(j, nv);
        for (int i = 0; i < nu; i++) {
            double a = once ? as[i] : offset(i, nu);
            bilinear(s, x + a * du[0] + b * dv[0], y + a * du[1] + b * dv[1], v);
            for (int c = 0; c < nc; c++)
                acc[c] += v[c];
        }
    }
    for (int c = 0; c < nc; c++)
        out[c] = acc[c] / (float)(nu * nv);
}

