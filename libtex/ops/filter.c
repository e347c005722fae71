/* filter.c - separable and 3x3 filters, median, noise, normal maps */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/progress.h"
#include "ops/filter.h"
#include "base/rng.h"

/* The hot loops are built for AVX-512, AVX2 and the baseline, and picked at
 * run time.  No clone contracts to FMA and each output sample is summed in
 * the same order, so all give the same bits. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define HOT __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define HOT
#endif

#define HB 64  /* floats per block of the horizontal pass */
#define VB 512 /* floats per strip of the vertical pass */
#define VROWS 32

static int colour_channels(const tex_map *m)
{
    return m->nc == 4 ? 3 : m->nc;
}

static tex_map *with_history(tex_map *o, const tex_map *m)
{
    if (o && m->history && tex_map_set_history(o, m->history) < 0) {
        tex_map_free(o);
        return NULL;
    }
    return o;
}

static tex_map *like(const tex_map *m, int nc)
{
    return with_history(tex_map_new(m->w, m->h, nc), m);
}

int tex_blur_radius(double sigma)
{
    double r = ceil(4.0 * sigma);
    return r < 1 ? 1 : r > 1e6 ? 1000000 : (int)r;
}

/* ---- separable convolution ---- */

/* A block of the passes: HB floats summed as four vectors of lanes held in registers through
 * the kernel's taps, where a sum kept in memory is loaded and stored again at every tap.
 * Each clone lowers the vectors to its own lanes (a zmm, two ymm, four xmm); each sample's sum
 * is the scalar loop's, in its order (HB is four vectors of 16). */
typedef float lanes __attribute__((vector_size(64), aligned(4), may_alias));
#define lanes_at(p) (*(const lanes *)(p))

/* out[b] = k0 c[b] + sum over j of kj (c[b - j step] + c[b + j step]), b < HB: four sums
 * in flight, named so that the compiler keeps them in registers */
static inline __attribute__((always_inline)) void taps_block(const float *c, ptrdiff_t step,
                                                             float *out, const float *k, int r)
{
    lanes a0 = k[0] * lanes_at(c), a1 = k[0] * lanes_at(c + 16);
    lanes a2 = k[0] * lanes_at(c + 32), a3 = k[0] * lanes_at(c + 48);
    for (int j = 1; j <= r; j++) {
        const float *lo = c - j * step, *hi = c + j * step;
        const float kj = k[j];
        a0 += kj * (lanes_at(lo) + lanes_at(hi));
        a1 += kj * (lanes_at(lo + 16) + lanes_at(hi + 16));
        a2 += kj * (lanes_at(lo + 32) + lanes_at(hi + 32));
        a3 += kj * (lanes_at(lo + 48) + lanes_at(hi + 48));
    }
    *(lanes *)out = a0, *(lanes *)(out + 16) = a1;
    *(lanes *)(out + 32) = a2, *(lanes *)(out + 48) = a3;
}

/* The same for len < HB samples, its sum kept in memory */
static inline __attribute__((always_inline)) void taps_tail(const float *c, ptrdiff_t step,
                                                            float *out, int len, const float *k,
                                                            int r)
{
    float acc[HB];
    const float k0 = k[0];
#pragma omp simd
    for (int b = 0; b < len; b++)
        acc[b] = k0 * c[b];
    for (int j = 1; j <= r; j++) {
        const float *lo = c - j * step, *hi = c + j * step;
        const float kj = k[j];
#pragma omp simd
        for (int b = 0; b < len; b++)
            acc[b] += kj * (lo[b] + hi[b]);
    }
    memcpy(out, acc, (size_t)len * sizeof *acc);
}

HOT static void hpass_row(const float *pad, float *out, int n, int nc, const float *k, int r)
{
    const float *c = pad + (size_t)r * nc;
    int i0 = 0;
    for (; i0 + HB <= n; i0 += HB)
        taps_block(c + i0, nc, out + i0, k, r);
    if (i0 < n)
        taps_tail(c + i0, nc, out + i0, n - i0, k, r);
}

/* Pixels x0..x1-1 of a row of w into pad, which holds pixel `first` first: those outside
 * the row copies by the edge rule, as far as the kernel reaches */
static void pad_edge(float *pad, long first, const float *row, long x0, long x1, int w, int nc,
                     enum tex_edge e)
{
    for (long x = x0; x < x1; x++)
        memcpy(pad + (size_t)(x - first) * nc, row + (size_t)tex_edge_index(x, w, e) * nc,
               nc * sizeof *pad);
}

/* A row's horizontal pass into out: its middle read where it is, its r pixels at each end
 * from pad (w + 2 r pixels) holding them and the pixels the kernel reaches, those beyond the
 * row by the edge rule; a row narrower than 2 r padded whole */
static void hpass(const float *row, float *out, int w, int nc, const float *k, int r,
                  enum tex_edge e, float *pad)
{
    int rn = r * nc, n = w * nc;

    if (w < 2 * r) {
        pad_edge(pad, -r, row, -r, w + r, w, nc, e);
        hpass_row(pad, out, n, nc, k, r);
        return;
    }
    pad_edge(pad, -r, row, -r, 2 * r, w, nc, e);
    hpass_row(pad, out, rn, nc, k, r);
    hpass_row(row, out + rn, n - 2 * rn, nc, k, r);
    pad_edge(pad, w - 2 * r, row, w - 2 * r, w + r, w, nc, e);
    hpass_row(pad, out + n - rn, rn, nc, k, r);
}

/* Rows y0..y1-1 of src's vertical pass into dst's rows y0-skip..: a row whose taps all lie
 * in src a block of lanes at a time, one nearer an edge than the kernel's reach by the rule */
HOT static void vpass_strip(const tex_map *src, tex_map *dst, int skip, int i0, int len, int y0,
                            int y1, const float *k, int r, enum tex_edge e)
{
    size_t stride = (size_t)src->w * src->nc;
    for (int y = y0; y < y1; y++) {
        const float *c = src->px + (size_t)y * stride + i0;
        float *o = dst->px + (size_t)(y - skip) * stride + i0;
        int b = 0;
        if (y >= r && y + r < src->h) {
            for (; b + HB <= len; b += HB)
                taps_block(c + b, (ptrdiff_t)stride, o + b, k, r);
            if (b < len)
                taps_tail(c + b, (ptrdiff_t)stride, o + b, len - b, k, r);
            continue;
        }
        float acc[VB];
        const float k0 = k[0];
#pragma omp simd
        for (int b = 0; b < len; b++)
            acc[b] = k0 * c[b];
        for (int j = 1; j <= r; j++) {
            const float *lo = src->px + (size_t)tex_edge_index(y - j, src->h, e) * stride + i0;
            const float *hi = src->px + (size_t)tex_edge_index(y + j, src->h, e) * stride + i0;
            const float kj = k[j];
#pragma omp simd
            for (int b = 0; b < len; b++)
                acc[b] += kj * (lo[b] + hi[b]);
        }
        memcpy(o, acc, (size_t)len * sizeof *acc);
    }
}

tex_map *tex_filter_separable_rows(const tex_map *m, const float *k, int r, enum tex_edge e,
                                   int skip)
{
    tex_map *tmp, *out;
    int nc = m->nc, n = m->w * m->nc, strips = (n + VB - 1) / VB, h = m->h - 2 * skip;
    int yblocks = (h + VROWS - 1) / VROWS, fail = 0;

    if (skip < 0 || h < 1) {
        tex_error("a band of %d rows has no rows between its %d rows of context", m->h, skip);
        return NULL;
    }
    /* both passes set every sample */
    if (!(tmp = tex_map_new_unset(m->w, m->h, nc)))
        return NULL;
    if (!(out = with_history(tex_map_new_unset(m->w, h, nc), m))) {
        tex_map_free(tmp);
        return NULL;
    }
    out->subregions = 0;
#pragma omp parallel
    {
        float *pad = malloc(((size_t)m->w + 2 * (size_t)r) * nc * sizeof *pad);
        if (!pad) {
#pragma omp atomic write
            fail = 1;
        }
        /* dynamic: a busy machine may stall one thread; each row is independent, so the
         * result does not depend on which thread takes it */
#pragma omp for schedule(dynamic, 8)
        for (int y = 0; y < m->h; y++) {
            if (pad)
                hpass(tex_map_row(m, y), tex_map_row(tmp, y), m->w, nc, k, r, e, pad);
        }
        free(pad);
    }
    if (fail) {
        tex_map_free(tmp);
        tex_map_free(out);
        tex_error("out of memory");
        return NULL;
    }
#pragma omp parallel for schedule(dynamic, 1)
    for (int t = 0; t < strips * yblocks; t++) {
        int s = t % strips, yb = t / strips;
        int i0 = s * VB, len = n - i0 < VB ? n - i0 : VB;
        int y0 = skip + yb * VROWS, y1 = y0 + VROWS < skip + h ? y0 + VROWS : skip + h;
        vpass_strip(tmp, out, skip, i0, len, y0, y1, k, r, e);
    }
    tex_map_free(tmp);
    return out;
}

tex_map *tex_filter_separable(const tex_map *m, const float *k, int r, enum tex_edge e)
{
    return tex_filter_separable_rows(m, k, r, e, 0);
}

/* t_filter's kernels must fit the map: wider ones would only repeat its edges. */
static int kernel_fits(const tex_map *m, int r)
{
    if (2L * r + 1 > m->w || 2L * r + 1 > m->h)
        return tex_usage_error("the kernel (%ld pixels wide) is larger than the %dx%d map",
                               2L * r + 1, m->w, m->h);
    return 0;
}

static tex_map *gaussian_rows(const tex_map *m, double sigma, enum tex_edge e, int skip)
{
    int r = tex_blur_radius(sigma);
    double sum = 0, *g = malloc(((size_t)r + 1) * sizeof *g);
    float *k = malloc(((size_t)r + 1) * sizeof *k);
    tex_map *out = NULL;

    if (!g || !k) {
        tex_error("out of memory");
    } else {
        for (int j = 0; j <= r; j++) {
            g[j] = exp(-(double)j * j / (2 * sigma * sigma));
            sum += j ? 2 * g[j] : g[j];
        }
        for (int j = 0; j <= r; j++)
            k[j] = (float)(g[j] / sum);
        out = tex_filter_separable_rows(m, k, r, e, skip);
    }
    free(g);
    free(k);
    return out;
}

tex_map *tex_filter_gaussian(const tex_map *m, double sigma, enum tex_edge e)
{
    return gaussian_rows(m, sigma, e, 0);
}

tex_map *tex_filter_blur_rows(const tex_map *m, double sigma, enum tex_edge e, int skip)
{
    if (!(sigma > 0) || !isfinite(sigma)) {
        tex_usage_error("the blur's sigma must be > 0 (got %g)", sigma);
        return NULL;
    }
    long width = 2L * tex_blur_radius(sigma) + 1;
    if (width > m->w || width > m->h) {
        tex_usage_error("sigma %g needs a kernel %ld pixels wide, larger than the %dx%d map", sigma,
                        width, m->w, m->h);
        return NULL;
    }
    return gaussian_rows(m, sigma, e, skip);
}

tex_map *tex_filter_blur(const tex_map *m, double sigma, enum tex_edge e)
{
    return tex_filter_blur_rows(m, sigma, e, 0);
}

tex_map *tex_filter_box_rows(const tex_map *m, int radius, enum tex_edge e, int skip)
{
    float *k;
    tex_map *out;

    if (radius < 1) {
        tex_usage_error("the box radius must be >= 1 (got %d)", radius);
        return NULL;
    }
    if (kernel_fits(m, radius) < 0)
        return NULL;
    if (!(k = malloc(((size_t)radius + 1) * sizeof *k))) {
        tex_error("out of memory");
        return NULL;
    }
    for (int j = 0; j <= radius; j++)
        k[j] = (float)(1.0 / (2.0 * radius + 1));
    out = tex_filter_separable_rows(m, k, radius, e, skip);
    free(k);
    return out;
}

tex_map *tex_filter_box(const tex_map *m, int radius, enum tex_edge e)
{
    return tex_filter_box_rows(m, radius, e, 0);
}

tex_map *tex_filter_smooth_rows(const tex_map *m, enum tex_edge e, int skip)
{
    static const float k[2] = {0.5f, 0.25f};
    return kernel_fits(m, 1) < 0 ? NULL : tex_filter_separable_rows(m, k, 1, e, skip);
}

tex_map *tex_filter_smooth(const tex_map *m, enum tex_edge e)
{
    return tex_filter_smooth_rows(m, e, 0);
}

tex_map *tex_filter_sharpen(const tex_map *m, double sigma, double amount, enum tex_edge e)
{
    tex_map *b = tex_filter_blur(m, sigma, e);
    int nc = m->nc, cc = colour_channels(m);
    size_t n = (size_t)m->w * m->h;
    float a = (float)amount;

    if (!b)
        return NULL;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < nc; c++) {
            float v = m->px[i * nc + c];
            b->px[i * nc + c] = c < cc ? v + a * (v - b->px[i * nc + c]) : v;
        }
    return b;
}

/* ---- 3x3 neighbourhoods ---- */

static inline float at(const tex_map *m, long x, long y, int c, enum tex_edge e)
{
    return m->px[((size_t)tex_edge_index(y, m->h, e) * m->w + tex_edge_index(x, m->w, e)) * m->nc +
                 c];
}

/* Sobel derivatives of channel c per pixel: gx to the right, gy downwards. */
static inline void sobel(const tex_map *m, long x, long y, int c, enum tex_edge e, float *gx,
                         float *gy)
{
    float a, b, d, f, g, h, i, j;
    /* inside the map: at()'s samples without the edge rule */
    if (x > 0 && x + 1 < m->w && y > 0 && y + 1 < m->h) {
        long nc = m->nc, row = (long)m->w * nc;
        const float *p = m->px + ((size_t)y * m->w + x) * m->nc + c;
        a = p[-row - nc], b = p[-row], d = p[-row + nc], f = p[-nc], g = p[nc];
        h = p[row - nc], i = p[row], j = p[row + nc];
    } else {
        a = at(m, x - 1, y - 1, c, e), b = at(m, x, y - 1, c, e), d = at(m, x + 1, y - 1, c, e);
        f = at(m, x - 1, y, c, e), g = at(m, x + 1, y, c, e);
        h = at(m, x - 1, y + 1, c, e), i = at(m, x, y + 1, c, e), j = at(m, x + 1, y + 1, c, e);
    }
    *gx = ((d + 2 * g + j) - (a + 2 * f + h)) * 0.125f;
    *gy = ((h + 2 * i + j) - (a + 2 * b + d)) * 0.125f;
}

/* A one-channel luminance map of m (m itself when it has one channel). */
static tex_map *height_of(const tex_map *m)
{
    tex_map *h;
    size_t n = (size_t)m->w * m->h;

    if (m->nc == 1)
        return (tex_map *)m;
    if (!(h = tex_map_new(m->w, m->h, 1)))
        return NULL;
    for (size_t i = 0; i < n; i++) {
        const float *p = m->px + i * m->nc;
        h->px[i] = m->nc >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    }
    return h;
}

tex_map *tex_filter_sobel(const tex_map *m, int direction, double scale, enum tex_edge e)
{
    tex_map *o = like(m, m->nc);
    int nc = m->nc, cc = colour_channels(m);
    float s = (float)scale;

    if (!o)
        return NULL;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            for (int c = 0; c < nc; c++) {
                float gx, gy, v;
                if (c >= cc) {
                    tex_map_px(o, x, y)[c] = tex_map_px(m, x, y)[c];
                    continue;
                }
                sobel(m, x, y, c, e, &gx, &gy);
                if (direction) {
                    v = gx == 0 && gy == 0 ? 0.0f : atan2f(-gy, gx) / (float)(2 * M_PI);
                    v = v < 0 ? v + 1.0f : v;
                } else
                    v = s * sqrtf(gx * gx + gy * gy);
                tex_map_px(o, x, y)[c] = v;
            }
    return o;
}

tex_map *tex_filter_edges(const tex_map *m, double amount, enum tex_edge e)
{
    tex_map *o = like(m, m->nc);
    int nc = m->nc, cc = colour_channels(m);
    float a = (float)amount;

    if (!o)
        return NULL;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            for (int c = 0; c < nc; c++) {
                float v = tex_map_px(m, x, y)[c];
                if (c < cc) {
                    float lap = at(m, x - 1, y, c, e) + at(m, x + 1, y, c, e) +
                                at(m, x, y - 1, c, e) + at(m, x, y + 1, c, e) - 4 * v;
                    v -= a * lap;
                }
                tex_map_px(o, x, y)[c] = v;
            }
    return o;
}

tex_map *tex_filter_emboss(const tex_map *m, double angle, double strength, enum tex_edge e)
{
    tex_map *o = like(m, m->nc);
    int nc = m->nc, cc = colour_channels(m);
    float lx = (float)cos(angle * M_PI / 180), ly = (float)sin(angle * M_PI / 180);
    float s = (float)strength;

    if (!o)
        return NULL;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            for (int c = 0; c < nc; c++) {
                float gx, gy;
                if (c >= cc) {
                    tex_map_px(o, x, y)[c] = tex_map_px(m, x, y)[c];
                    continue;
                }
                sobel(m, x, y, c, e, &gx, &gy);
                /* slopes rising away from the light face it: bright */
                tex_map_px(o, x, y)[c] = 0.5f - s * (gx * lx - gy * ly);
            }
    return o;
}

/* The Sobel slopes of a map's height: a tangent-space normal map of strength k
 * (normal set), or the 2-channel gradient (Fu, Fv) per unit of texture space. */
static tex_map *slopes(const tex_map *m, enum tex_edge e, int normal, float k, int full_h)
{
    tex_map *h = height_of(m), *o;

    if (!h)
        return NULL;
    if (!(o = like(m, normal ? 3 : 2))) {
        if (h != m)
            tex_map_free(h);
        return NULL;
    }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++) {
            float gx, gy, *p = tex_map_px(o, x, y);
            sobel(h, x, y, 0, e, &gx, &gy);
            if (normal) {
                float nx = -k * gx, ny = k * gy, len = sqrtf(nx * nx + ny * ny + 1.0f);
                p[0] = 0.5f + 0.5f * nx / len;
                p[1] = 0.5f + 0.5f * ny / len;
                p[2] = 0.5f + 0.5f / len;
            } else {
                p[0] = gx * (float)m->w;
                p[1] = gy * (float)full_h;
            }
        }
    if (h != m)
        tex_map_free(h);
    return o;
}

tex_map *tex_filter_normal(const tex_map *m, double strength, enum tex_edge e)
{
    return slopes(m, e, 1, (float)strength, m->h);
}

tex_map *tex_filter_gradient(const tex_map *m, enum tex_edge e)
{
    return slopes(m, e, 0, 0.0f, m->h);
}

tex_map *tex_filter_gradient_rows(const tex_map *m, enum tex_edge e, int full_h)
{
    return slopes(m, e, 0, 0.0f, full_h);
}

/* ---- median ---- */

static float select_kth(float *a, int n, int k)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        float pivot = a[(lo + hi) / 2];
        int i = lo, j = hi;
        while (i <= j) {
            while (a[i] < pivot)
                i++;
            while (a[j] > pivot)
                j--;
            if (i <= j) {
                float t = a[i];
                a[i++] = a[j];
                a[j--] = t;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            break;
    }
    return a[k];
}

tex_map *tex_filter_median(const tex_map *m, int radius, enum tex_edge e)
{
    tex_map *o;
    int side = 2 * radius + 1, n = side * side, fail = 0;

    if (radius < 1 || radius > 15) {
        tex_usage_error("the median radius must be 1..15 (got %d)", radius);
        return NULL;
    }
    if (side > m->w || side > m->h) {
        tex_usage_error("the median window (%d pixels) is larger than the %dx%d map", side, m->w,
                        m->h);
        return NULL;
    }
    if (!(o = like(m, m->nc)))
        return NULL;
    tex_progress_stage(1, m->h);
#pragma omp parallel
    {
        float *win = malloc((size_t)n * sizeof *win);
        if (!win) {
#pragma omp atomic write
            fail = 1;
        }
#pragma omp for schedule(static)
        for (int y = 0; y < m->h; y++) {
            for (int x = 0; x < m->w && win; x++)
                for (int c = 0; c < m->nc; c++) {
                    int k = 0;
                    for (int dy = -radius; dy <= radius; dy++)
                        for (int dx = -radius; dx <= radius; dx++)
                            win[k++] = at(m, (long)x + dx, (long)y + dy, c, e);
                    tex_map_px(o, x, y)[c] = select_kth(win, n, n / 2);
                }
            tex_progress_add(1);
        }
        free(win);
    }
    if (fail) {
        tex_map_free(o);
        tex_error("out of memory");
        return NULL;
    }
    return o;
}

/* ---- additive Gaussian noise ---- */

tex_map *tex_filter_noise(const tex_map *m, double sd, uint64_t seed)
{
    return tex_filter_noise_rows(m, sd, seed, 0);
}

tex_map *tex_filter_noise_rows(const tex_map *m, double sd, uint64_t seed, int y0)
{
    tex_map *o = like(m, m->nc);
    size_t n = tex_map_samples(m);
    int nc = m->nc, cc = colour_channels(m);
    uint64_t key = tex_hash64(seed ^ 0x6e6f697365ULL); /* "noise" */
    uint64_t first = (uint64_t)y0 * m->w * nc;

    if (!o)
        return NULL;
    o->subregions = 0;
    /* Each sample's noise is a hash of (seed, sample index): no shared state. */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        float v = m->px[i];
        if ((int)(i % nc) < cc) {
            uint64_t h1 = tex_hash64(key + 2 * (first + i)), h2 = tex_hash64(key + 2 * (first + i) + 1);
            double u1 = ((h1 >> 11) + 1) * 0x1p-53, u2 = (h2 >> 11) * 0x1p-53;
            v += (float)(sd * sqrt(-2 * log(u1)) * cos(2 * M_PI * u2));
        }
        o->px[i] = v;
    }
    return o;
}
