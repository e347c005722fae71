/* spectral.c - FFT and inverse FFT of maps, spectral synthesis of fBm,
 * Lewis's sparse convolution, and the spectral primitive */
#include <fftw3.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/error.h"
#include "base/map.h"
#include "base/progress.h"
#include "prim/prim.h"
#include "base/rng.h"
#include "prim/spectral.h"

/* ---- FFTW set-up, threads, the random phase table ---- */

static pthread_once_t setup_once = PTHREAD_ONCE_INIT;
static int fftw_threads_ok;

#define PHASE_BITS 12
#define PHASE_N (1 << PHASE_BITS)
/* cos and sin of PHASE_N evenly spaced angles: random phases come from a
 * hash of the frequency and this table, not from a cos/sin per pixel. */
static float phase_cs[PHASE_N][2];

static void setup(void)
{
    fftw_threads_ok = fftwf_init_threads() != 0;
    if (fftw_threads_ok)
        fftwf_make_planner_thread_safe();
    for (int i = 0; i < PHASE_N; i++) {
        double a = 2.0 * M_PI * i / PHASE_N;
        phase_cs[i][0] = (float)cos(a);
        phase_cs[i][1] = (float)sin(a);
    }
}

/* Plans use as many threads as OpenMP (-j).  ESTIMATE plans do not depend
 * on timings, and FFTW's threads split independent rows and columns, so the
 * bits do not depend on the thread count (tests/prim/spectral.sh checks it). */
static void plan_setup(void)
{
    pthread_once(&setup_once, setup);
#ifdef _OPENMP
    if (fftw_threads_ok)
        fftwf_plan_with_nthreads(omp_get_max_threads());
#endif
}

/* FFTW's arrays in pages of their own (tex_pages_new), 64-byte aligned as fftwf_malloc's
 * are: on the heap a 2048^2 map's were 8,000 first touches of 4 KiB pages.  The mapping's
 * size is kept in the 64 bytes before the array. */
#define FFT_PAGES (1 << 20)
static void *fft_alloc(size_t bytes)
{
    size_t mapped;
    unsigned char *p = tex_pages_new(bytes + 64, FFT_PAGES, &mapped);
    if (!p)
        return NULL;
    memcpy(p, &mapped, sizeof mapped);
    return p + 64;
}

static void fft_free(void *a)
{
    size_t mapped;
    if (!a)
        return;
    memcpy(&mapped, (unsigned char *)a - 64, sizeof mapped);
    tex_pages_free((unsigned char *)a - 64, mapped);
}

static float *fft_real(size_t n)
{
    return fft_alloc(n * sizeof(float));
}

static fftwf_complex *fft_complex(size_t n)
{
    return fft_alloc(n * sizeof(fftwf_complex));
}

/* Transforms are the long part of this module's work: each is a unit of progress. */
static void execute(fftwf_plan plan)
{
    fftwf_execute(plan);
    tex_progress_add(1);
}

static inline const float *random_phase(uint64_t key, uint64_t k)
{
    return phase_cs[tex_hash64(key + k) >> (64 - PHASE_BITS)];
}

/* ---- helpers ---- */

/* The finite check and, in the same pass, whether any sample is nonzero. */
static int scan(const tex_map *m, const char *what, int *nonzero)
{
    size_t n = tex_map_samples(m), bad = n;
    int nz = 0;

#pragma omp parallel for schedule(static) reduction(min : bad) reduction(| : nz)
    for (size_t i = 0; i < n; i++) {
        float v = m->px[i];
        if (!isfinite(v) && i < bad)
            bad = i;
        nz |= v != 0.0f;
    }
    if (nonzero)
        *nonzero = nz;
    if (bad < n) {
        size_t p = bad / m->nc;
        return tex_error("%s%spixel (%zu,%zu) is not a finite number", what ? what : "",
                         what ? ": " : "", p % m->w, p / m->w);
    }
    return 0;
}

int tex_check_finite(const tex_map *m, const char *what)
{
    return scan(m, what, NULL);
}

/* The scalar of each pixel (see spectral.h); *owned is set when it is a copy. */
static const float *scalar_of(const tex_map *m, float **owned)
{
    size_t n = (size_t)m->w * m->h;
    float *s;

    *owned = NULL;
    if (m->nc == 1)
        return m->px;
    if (!(s = malloc(n * sizeof *s))) {
        tex_error("out of memory");
        return NULL;
    }
#pragma omp parallel for
    for (size_t i = 0; i < n; i++) {
        const float *p = m->px + i * m->nc;
        s[i] = m->nc < 3 ? p[0] : 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    }
    *owned = s;
    return s;
}

static void minmax(const float *v, size_t n, size_t stride, float *lo, float *hi)
{
    float a = INFINITY, b = -INFINITY;

#pragma omp parallel for reduction(min : a) reduction(max : b)
    for (size_t i = 0; i < n; i++) {
        float x = v[i * stride];
        a = x < a ? x : a;
        b = x > b ? x : b;
    }
    *lo = a;
    *hi = b;
}

/* Rescale n values to [0,1] by min and max (by max alone if from_zero). */
static void to_unit(float *v, size_t n, int from_zero)
{
    float lo, hi;

    minmax(v, n, 1, &lo, &hi);
    if (from_zero)
        lo = 0;
    if (!(hi > lo)) {
#pragma omp parallel for
        for (size_t i = 0; i < n; i++)
            v[i] = v[i] < 0 ? 0 : v[i] > 1 ? 1 : v[i];
        return;
    }
    float sc = 1.0f / (hi - lo);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) /* the maximum maps to exactly 1 */
        v[i] = v[i] == hi ? 1.0f : (v[i] - lo) * sc;
}

static inline float turns(float im, float re)
{
    float t = atan2f(im, re) * (float)(0.5 / M_PI);
    return t < 0 ? t + 1.0f : t >= 1.0f ? 0.0f : t;
}

/* ---- the forward transform ---- */

/* The transform's input: s windowed (Hann where hann, else flat; wx: w + h floats of
 * scratch) and scaled by the window's mean and 1/(w h) */
static void windowed_input(const float *s, int w, int h, int hann, float *wx, float *in)
{
    float *wy = wx + w;
    double gx = 0, gy = 0, g;
    for (int x = 0; x < w; x++)
        gx += wx[x] = hann ? (float)(0.5 - 0.5 * cos(2 * M_PI * (x + 0.5) / w)) : 1.0f;
    for (int y = 0; y < h; y++)
        gy += wy[y] = hann ? (float)(0.5 - 0.5 * cos(2 * M_PI * (y + 0.5) / h)) : 1.0f;
    /* Dividing by the window's mean keeps amplitudes; 1/(w h) normalises. */
    g = 1.0 / (gx * gy);
#pragma omp parallel for
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            in[(size_t)y * w + x] = (float)(s[(size_t)y * w + x] * wx[x] * wy[y] * g);
}

/* The half spectrum F of a w x h real map as o's rows, zero frequency at the centre:
 * complex, phase in turns or magnitude */
static void spectrum_rows(const fftwf_complex *F, int w, int h, enum tex_fft_output out,
                          tex_map *o)
{
    int hw = w / 2 + 1;
#pragma omp parallel for
    for (int y = 0; y < h; y++) {
        int ky = (y - h / 2 + h) % h, kyc = (h - ky) % h;
        float *row = tex_map_row(o, y);
        for (int x = 0; x < w; x++) {
            int kx = (x - w / 2 + w) % w;
            float re, im;
            if (kx < hw) {
                re = F[(size_t)ky * hw + kx][0];
                im = F[(size_t)ky * hw + kx][1];
            } else { /* the other half, by the symmetry of a real map's spectrum */
                re = F[(size_t)kyc * hw + (w - kx)][0];
                im = -F[(size_t)kyc * hw + (w - kx)][1];
            }
            switch (out) {
            case TEX_FFT_COMPLEX:
                row[2 * x] = re;
                row[2 * x + 1] = im;
                break;
            case TEX_FFT_PHASE:
                row[x] = turns(im, re);
                break;
            default:
                row[x] = hypotf(re, im);
            }
        }
    }
}

static tex_map *fft(const tex_map *m, enum tex_fft_output out, int hann)
{
    int w = m->w, h = m->h, hw = w / 2 + 1;
    tex_progress_stage(1, 1);
    float *own = NULL, *in = NULL, *wx = NULL;
    fftwf_complex *F = NULL;
    const float *s;
    tex_map *o = NULL;
    fftwf_plan plan;

    if (tex_check_finite(m, NULL) < 0 || !(s = scalar_of(m, &own)))
        return NULL;
    in = fft_real((size_t)w * h);
    F = fft_complex((size_t)h * hw);
    wx = malloc(((size_t)w + h) * sizeof *wx);
    if (!in || !F || !wx) {
        tex_error("out of memory");
        goto done;
    }
    windowed_input(s, w, h, hann, wx, in);
    plan_setup();
    plan = fftwf_plan_dft_r2c_2d(h, w, in, F, FFTW_ESTIMATE);
    if (!plan) {
        tex_error("FFTW could not plan a %dx%d transform", w, h);
        goto done;
    }
    execute(plan);
    fftwf_destroy_plan(plan);
    if (!(o = tex_map_new(w, h, out == TEX_FFT_COMPLEX ? 2 : 1)))
        goto done;
    spectrum_rows(F, w, h, out, o);
    if (out == TEX_FFT_LOGMAG) {
        size_t n = (size_t)w * h;
        float lo, hi, wh = (float)n, l;
        minmax(o->px, n, 1, &lo, &hi);
        l = hi > 0 ? 1.0f / log1pf(wh * hi) : 0.0f;
#pragma omp parallel for
        for (size_t i = 0; i < n; i++)
            o->px[i] = log1pf(wh * o->px[i]) * l;
    }
done:
    free(own);
    free(wx);
    fft_free(in);
    fft_free(F);
    return o;
}

/* ---- the inverse transform of a painted or computed spectrum ---- */

struct ifft_ctx {
    int w, h, complex;
    const float *mag;   /* magnitude (scalar) or NULL */
    const float *cplx;  /* Re, Im interleaved, or NULL */
    const float *phase; /* turns, or NULL */
    enum tex_ifft_phase mode;
    uint64_t key;
};

/* cos and sin of the phase at centred pixel p. */
static inline void phase_at(const struct ifft_ctx *c, size_t p, float *cs, float *sn)
{
    if (c->mode == TEX_PHASE_RANDOM) {
        const float *t = random_phase(c->key, p);
        *cs = t[0];
        *sn = t[1];
    } else if (c->mode == TEX_PHASE_ZERO) {
        *cs = 1.0f;
        *sn = 0.0f;
    } else {
        float a = (float)(2.0 * M_PI) * c->phase[p];
        *cs = cosf(a);
        *sn = sinf(a);
    }
}

/* Fill the half spectrum (h x (w/2+1), FFTW's layout) by Hermitian completion. */
static void fill_half(const struct ifft_ctx *c, fftwf_complex *F)
{
    int w = c->w, h = c->h, hw = w / 2 + 1;

#pragma omp parallel for schedule(static)
    for (int ky = 0; ky < h; ky++) {
        int y = ky + h / 2, yq = (h - ky) % h + h / 2;
        fftwf_complex *row = F + (size_t)ky * hw;
        y -= y >= h ? h : 0;
        yq -= yq >= h ? h : 0;
        for (int kx = 0; kx < hw; kx++) {
            int x = kx + w / 2, xq = (kx ? w - kx : 0) + w / 2;
            size_t p, q;
            x -= x >= w ? w : 0;
            xq -= xq >= w ? w : 0;
            p = (size_t)y * w + x;
            q = (size_t)yq * w + xq;
            if (c->complex) {
                row[kx][0] = 0.5f * (c->cplx[2 * p] + c->cplx[2 * q]);
                row[kx][1] = 0.5f * (c->cplx[2 * p + 1] - c->cplx[2 * q + 1]);
                continue;
            }
            float mp = c->mag[p], mq = c->mag[q], cs, sn;
            if (p == q) { /* self-conjugate: DC and Nyquist terms are real */
                phase_at(c, p, &cs, &sn);
                row[kx][0] = mp * cs;
                row[kx][1] = 0.0f;
            } else if (mp > mq || (mp == mq && p < q)) {
                phase_at(c, p, &cs, &sn);
                row[kx][0] = mp * cs;
                row[kx][1] = mp * sn;
            } else {
                phase_at(c, q, &cs, &sn);
                row[kx][0] = mq * cs;
                row[kx][1] = -mq * sn;
            }
        }
    }
}

/* Fill the full spectrum (h x w, FFTW's layout) as painted. */
static void fill_full(const struct ifft_ctx *c, fftwf_complex *F)
{
    int w = c->w, h = c->h;

#pragma omp parallel for schedule(static)
    for (int ky = 0; ky < h; ky++) {
        int y = ky + h / 2;
        fftwf_complex *row = F + (size_t)ky * w;
        y -= y >= h ? h : 0;
        for (int kx = 0; kx < w; kx++) {
            int x = kx + w / 2;
            size_t p;
            x -= x >= w ? w : 0;
            p = (size_t)y * w + x;
            if (c->complex) {
                row[kx][0] = c->cplx[2 * p];
                row[kx][1] = c->cplx[2 * p + 1];
            } else {
                float cs, sn;
                phase_at(c, p, &cs, &sn);
                row[kx][0] = c->mag[p] * cs;
                row[kx][1] = c->mag[p] * sn;
            }
        }
    }
}

static int all_zero(const float *v, size_t n, size_t stride)
{
    int nz = 0;

#pragma omp parallel for reduction(| : nz)
    for (size_t i = 0; i < n; i++)
        nz |= v[i * stride] != 0.0f;
    return !nz;
}

/* The spectrum's magnitude and phase, or its complex coefficients, into c;
 * 0, or -1 with the error set (own, ownp: copies for the caller to free). */
static int ifft_inputs(const tex_map *s, const struct tex_ifft_opts *o, struct ifft_ctx *c,
                       float **own, float **ownp)
{
    int nonzero;
    if (scan(s, NULL, &nonzero) < 0)
        return -1;
    if (s->nc == 2) {
        c->cplx = s->px;
        if (!nonzero)
            return tex_error("every coefficient of the spectrum is zero (nothing to invert)");
        return 0;
    }
    if (!(c->mag = scalar_of(s, own)))
        return -1;
    if (!nonzero || (s->nc > 2 && all_zero(c->mag, (size_t)s->w * s->h, 1)))
        return tex_error("the magnitude is zero everywhere (nothing to invert)");
    if (o->phase != TEX_PHASE_MAP)
        return 0;
    if (!o->phase_map)
        return tex_usage_error("a phase map is needed");
    if (o->phase_map->w != s->w || o->phase_map->h != s->h)
        return tex_error("the phase map is %dx%d but the spectrum is %dx%d", o->phase_map->w,
                         o->phase_map->h, s->w, s->h);
    if (tex_check_finite(o->phase_map, "phase map") < 0 ||
        !(c->phase = scalar_of(o->phase_map, ownp)))
        return -1;
    return 0;
}

static int no_plan(int w, int h)
{
    return tex_error("FFTW could not plan a %dx%d transform", w, h);
}

/* A Hermitian spectrum: c2r, straight into the map when the real part is
 * all we want. */
static int ifft_half(const struct ifft_ctx *c, const struct tex_ifft_opts *o, tex_map *out)
{
    int w = c->w, h = c->h, rc = 0;
    size_t n = (size_t)w * h;
    float *rbuf = NULL, *r = o->output == TEX_IFFT_REAL ? out->px : (rbuf = fft_real(n));
    fftwf_complex *F = fft_complex((size_t)h * (w / 2 + 1));
    fftwf_plan plan = NULL;
    if (!r || !F)
        rc = tex_error("out of memory");
    else if (!(plan = fftwf_plan_dft_c2r_2d(h, w, F, r, FFTW_ESTIMATE)))
        rc = no_plan(w, h);
    if (rc == 0) {
        fill_half(c, F);
        execute(plan);
    }
    if (rc == 0 && o->output != TEX_IFFT_REAL) {
#pragma omp parallel for
        for (size_t i = 0; i < n; i++) {
            float v = r[i];
            switch (o->output) {
            case TEX_IFFT_MAG: out->px[i] = fabsf(v); break;
            case TEX_IFFT_LOGMAG: out->px[i] = log1pf(fabsf(v)); break;
            case TEX_IFFT_PHASE: out->px[i] = v < 0 ? 0.5f : 0.0f; break;
            default: out->px[2 * i] = v; out->px[2 * i + 1] = 0.0f;
            }
        }
    }
    if (plan)
        fftwf_destroy_plan(plan);
    fft_free(rbuf);
    fft_free(F);
    return rc;
}

/* Any spectrum: a complex transform in place, then the part asked for. */
static int ifft_full(const struct ifft_ctx *c, const struct tex_ifft_opts *o, tex_map *out)
{
    int w = c->w, h = c->h;
    size_t n = (size_t)w * h;
    fftwf_complex *F = fft_complex(n);
    fftwf_plan plan;
    if (!F)
        return tex_error("out of memory");
    if (!(plan = fftwf_plan_dft_2d(h, w, F, F, FFTW_BACKWARD, FFTW_ESTIMATE))) {
        fft_free(F);
        return no_plan(w, h);
    }
    fill_full(c, F);
    execute(plan);
#pragma omp parallel for
    for (size_t i = 0; i < n; i++) {
        float re = F[i][0], im = F[i][1];
        switch (o->output) {
        case TEX_IFFT_REAL: out->px[i] = re; break;
        case TEX_IFFT_MAG: out->px[i] = hypotf(re, im); break;
        case TEX_IFFT_LOGMAG: out->px[i] = log1pf(hypotf(re, im)); break;
        case TEX_IFFT_PHASE: out->px[i] = turns(im, re); break;
        default: out->px[2 * i] = re; out->px[2 * i + 1] = im;
        }
    }
    fftwf_destroy_plan(plan);
    fft_free(F);
    return 0;
}

static tex_map *ifft(const tex_map *s, const struct tex_ifft_opts *o)
{
    int w = s->w, h = s->h, cplx = s->nc == 2;
    struct ifft_ctx c = {w, h, cplx, NULL, NULL, NULL, o->phase, tex_hash64(o->seed)};
    enum tex_ifft_scale scale = o->scale;
    float *own = NULL, *ownp = NULL;
    tex_map *out = NULL;

    tex_progress_stage(1, 1);
    if (scale == TEX_SCALE_AUTO)
        scale = cplx ? TEX_SCALE_NONE : TEX_SCALE_UNIT;
    if (ifft_inputs(s, o, &c, &own, &ownp) == 0 &&
        (out = tex_map_new(w, h, o->output == TEX_IFFT_COMPLEX ? 2 : 1))) {
        plan_setup();
        if ((o->symmetric ? ifft_half(&c, o, out) : ifft_full(&c, o, out)) < 0) {
            tex_map_free(out);
            out = NULL;
        } else if (scale == TEX_SCALE_UNIT && o->output != TEX_IFFT_PHASE &&
                   o->output != TEX_IFFT_COMPLEX) {
            to_unit(out->px, (size_t)w * h, o->output != TEX_IFFT_REAL);
        }
    }
    free(own);
    free(ownp);
    return out;
}

/* ---- spectral synthesis of fBm ---- */

/* x^e for float x > 0 without a libm call per frequency: with x = m 2^E,
 * m in [1,2), x^e = m^e 2^(E e), the first from a table over the top ten
 * bits of the mantissa with linear interpolation (relative error about
 * 1e-7 |e (e-1)|), the second from a table over the exponent. */
#define POW_BITS 10
struct powtab {
    float m[(1 << POW_BITS) + 1];
    float p[256];
};

static void powtab_init(struct powtab *t, double e)
{
    for (int i = 0; i <= 1 << POW_BITS; i++)
        t->m[i] = (float)pow(1.0 + (double)i / (1 << POW_BITS), e);
    for (int j = 0; j < 256; j++)
        t->p[j] = (float)fmin(exp2((j - 127) * e), 3.4e38);
}

static inline float powtab_eval(const struct powtab *t, float x)
{
    union {
        float f;
        uint32_t i;
    } u = {x};
    uint32_t i = (u.i >> (23 - POW_BITS)) & ((1u << POW_BITS) - 1);
    float frac = (float)(u.i & ((1u << (23 - POW_BITS)) - 1)) * (1.0f / (1 << (23 - POW_BITS)));
    float m = t->m[i] + (t->m[i + 1] - t->m[i]) * frac;
    return m * t->p[(u.i >> 23) & 255];
}

/* tex_spectral_fbm, its messages naming the band as band does ("--band") */
static int spectral_fbm(tex_map *m, const struct tex_fbm_spec *p, const char *band)
{
    int w = m->w, h = m->h, hw = w / 2 + 1, any = 0;
    size_t n = (size_t)w * h;
    double side = w > h ? w : h, a = p->angle * M_PI / 180.0;
    /* Frequencies in cycles across the longer side; the stretch direction
     * on the screen (y down). */
    float sx = (float)(side / w), sy = (float)(side / h), dx = (float)cos(a), dy = (float)-sin(a);
    float r2 = (float)(p->ratio * p->ratio) - 1.0f, e = (float)(-(p->h + 1.0) / 2.0);
    float lo2 = (float)(p->lo * p->lo), hi2 = (float)(p->hi * p->hi);
    uint64_t key = tex_hash64(p->seed ^ 0x5bd1e995u);
    fftwf_complex *F;
    fftwf_plan plan;
    struct powtab pt;

    tex_progress_stage(1, 1);
    if (m->nc != 1)
        return tex_error("internal: fBm fills a 1-channel map");
    if (!(F = fft_complex((size_t)h * hw)))
        return tex_error("out of memory");
    powtab_init(&pt, e);
    plan_setup();
    if (!(plan = fftwf_plan_dft_c2r_2d(h, w, F, m->px, FFTW_ESTIMATE))) {
        fft_free(F);
        return tex_error("FFTW could not plan a %dx%d transform", w, h);
    }
#pragma omp parallel for schedule(static) reduction(| : any)
    for (int ky = 0; ky < h; ky++) {
        int kys = ky <= h / 2 ? ky : ky - h, kyc = (h - ky) % h;
        float fy = (float)kys * sy;
        fftwf_complex *row = F + (size_t)ky * hw;
        for (int kx = 0; kx < hw; kx++) {
            float fx = (float)kx * sx, f2 = fx * fx + fy * fy, par = fx * dx + fy * dy, amp;
            const float *cs;
            uint64_t k = (uint64_t)ky * w + kx;
            int conj = 0;
            if (f2 == 0.0f || f2 < lo2 || f2 > hi2) {
                row[kx][0] = row[kx][1] = 0.0f;
                continue;
            }
            amp = powtab_eval(&pt, f2 + r2 * par * par);
            any = 1;
            /* Columns 0 and w/2 hold both k and -k: give the pair one phase. */
            if (kx == 0 || 2 * kx == w) {
                if (kyc < ky) {
                    k = (uint64_t)kyc * w + kx;
                    conj = 1;
                } else if (kyc == ky) { /* self-conjugate: real */
                    row[kx][0] = amp * random_phase(key, k)[0];
                    row[kx][1] = 0.0f;
                    continue;
                }
            }
            cs = random_phase(key, k);
            row[kx][0] = amp * cs[0];
            row[kx][1] = conj ? -amp * cs[1] : amp * cs[1];
        }
    }
    if (!any) {
        fftwf_destroy_plan(plan);
        fft_free(F);
        return tex_usage_error("%s %g,%g holds no frequency of a %dx%d map (1 is the lowest, %g "
                               "the highest)",
                               band, p->lo, p->hi, w, h, sqrt(2.0) * side / 2);
    }
    execute(plan);
    fftwf_destroy_plan(plan);
    fft_free(F);
    to_unit(m->px, n, 0);
    return 0;
}

/* ---- Lewis's sparse convolution ---- */

/* Sparse convolution's buffers: the map's real plane rb, the sample's
 * window win, the noise's spectrum I, the working spectrum K. */
struct sparse_work {
    int w, h;
    size_t n, nhalf;
    float *rb, *win;
    fftwf_complex *I, *K;
    fftwf_plan fwd, inv;
};

/* The white noise, weights in [-1,1] at uniform pixel positions, into I. */
static void sparse_noise(struct sparse_work *k, double count, uint64_t seed)
{
    tex_rng rng;
    memset(k->rb, 0, k->n * sizeof *k->rb);
    tex_rng_seed(&rng, seed);
    for (long long i = 0, N = llround(count) > 0 ? llround(count) : 1; i < N; i++) {
        uint32_t x = tex_rng_below(&rng, (uint32_t)k->w), y = tex_rng_below(&rng, (uint32_t)k->h);
        k->rb[(size_t)y * k->w + x] += (float)(2.0 * tex_rng_uniform(&rng) - 1.0);
    }
    execute(k->fwd);
    memcpy(k->I, k->K, k->nhalf * sizeof *k->I);
}

/* Channel c of the sample, windowed and convolved with the noise, rescaled
 * to the sample's range into channel c of out. */
static void sparse_channel(struct sparse_work *k, const tex_map *s, int c, tex_map *out)
{
    int sw = s->w, sh = s->h, nc = s->nc, w = k->w, h = k->h;
    size_t n = k->n, sn = (size_t)sw * sh;
    double sum = 0, sum2 = 0, mean, sd;
    float lo = INFINITY, hi = -INFINITY, *rb = k->rb;
    for (size_t i = 0; i < sn; i++) {
        float v = s->px[i * nc + c];
        sum += v;
        sum2 += (double)v * v;
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    mean = sum / sn;
    sd = sqrt(fmax(0.0, sum2 / sn - mean * mean));
    if (!(sd > 0) || !(hi > lo)) { /* a constant channel stays constant */
        for (size_t i = 0; i < n; i++)
            out->px[i * nc + c] = (float)mean;
        return;
    }
    /* The windowed sample, centred on the origin, wrapping around. */
    memset(rb, 0, n * sizeof *rb);
    for (int y = 0; y < sh; y++)
        for (int x = 0; x < sw; x++) {
            int X = (x - sw / 2 + w) % w, Y = (y - sh / 2 + h) % h;
            rb[(size_t)Y * w + X] =
                (float)((s->px[((size_t)y * sw + x) * nc + c] - mean) * k->win[(size_t)y * sw + x]);
        }
    execute(k->fwd);
    fftwf_complex *K = k->K, *I = k->I;
#pragma omp parallel for
    for (size_t i = 0; i < k->nhalf; i++) {
        float re = K[i][0] * I[i][0] - K[i][1] * I[i][1];
        float im = K[i][0] * I[i][1] + K[i][1] * I[i][0];
        K[i][0] = re;
        K[i][1] = im;
    }
    execute(k->inv);
    float flo, fhi;
    minmax(rb, n, 1, &flo, &fhi);
    double g = fhi > flo ? (hi - lo) / ((double)fhi - flo) : 0;
#pragma omp parallel for
    for (size_t i = 0; i < n; i++) {
        float v = (float)(lo + (rb[i] - flo) * g);
        out->px[i * nc + c] = v > hi ? hi : v;
    }
}

static tex_map *sparse_convolve(const tex_map *s, int w, int h, const struct tex_sparse_spec *p)
{
    int sw = s->w, sh = s->h, hw = w / 2 + 1;
    struct sparse_work k = {w, h, (size_t)w * h, (size_t)h * hw, NULL, NULL, NULL, NULL, NULL, NULL};
    double count = p->density * (double)k.n / ((double)sw * sh);
    tex_map *out = NULL;

    if (sw > w || sh > h) {
        tex_usage_error("the sample (%dx%d) is larger than the map (%dx%d); give a larger -s", sw,
                        sh, w, h);
        return NULL;
    }
    if (count > 1e9) {
        tex_usage_error("--density %g asks for %.3g impulses (at most 1e9)", p->density, count);
        return NULL;
    }
    if (tex_check_finite(s, NULL) < 0)
        return NULL;
    k.rb = fft_real(k.n);
    k.win = malloc((size_t)sw * sh * sizeof *k.win);
    k.I = fft_complex(k.nhalf);
    k.K = fft_complex(k.nhalf);
    if (!k.rb || !k.win || !k.I || !k.K || !(out = tex_map_new(w, h, s->nc))) {
        tex_error("out of memory");
    } else {
        plan_setup();
        k.fwd = fftwf_plan_dft_r2c_2d(h, w, k.rb, k.K, FFTW_ESTIMATE);
        k.inv = fftwf_plan_dft_c2r_2d(h, w, k.K, k.rb, FFTW_ESTIMATE);
        if (!k.fwd || !k.inv) {
            tex_error("FFTW could not plan a %dx%d transform", w, h);
            tex_map_free(out);
            out = NULL;
        }
    }
    if (out) {
        tex_progress_stage(1, 1 + 2 * s->nc); /* the impulses' transform, two per channel */
        sparse_noise(&k, count, p->seed);
        for (int y = 0; y < sh; y++)
            for (int x = 0; x < sw; x++) {
                double rx = (x + 0.5 - sw / 2.0) / (sw / 2.0), ry = (y + 0.5 - sh / 2.0) / (sh / 2.0);
                k.win[(size_t)y * sw + x] = (float)exp(-p->falloff * sqrt(rx * rx + ry * ry));
            }
        for (int c = 0; c < s->nc; c++)
            sparse_channel(&k, s, c, out);
    }
    if (k.fwd)
        fftwf_destroy_plan(k.fwd);
    if (k.inv)
        fftwf_destroy_plan(k.inv);
    fft_free(k.rb);
    fft_free(k.I);
    fft_free(k.K);
    free(k.win);
    return out;
}

int tex_spectral_fbm(tex_map *m, const struct tex_fbm_spec *p)
{
    return spectral_fbm(m, p, "the band");
}

/* ---- the spectral primitive ---- */

struct spectral_params {
    double h;
    double dimension;
    struct tex_reals anisotropy;
    struct tex_reals band;
};

#define HURST 0.8 /* the default: another value beside --fractal-dimension is refused */
#define DIMENSION_MIN 2 /* a surface's fractal dimension, 2..3; 0 is none */
#define DIMENSION_MAX 3
static const struct tex_param spectral_rows[] = {
    TEX_REAL_N("hurst", struct spectral_params, h, 0, HURST, -1, 3, "H",
               "Hurst exponent: the amplitude falls as f^-(H+1)", .alias = "h"),
    TEX_REAL_N("fractal_dimension", struct spectral_params, dimension, 'D', 0, 0, DIMENSION_MAX,
               "D",
               "fractal dimension " TEX_XSTR(DIMENSION_MIN) ".." TEX_XSTR(DIMENSION_MAX) " of "
               "the surface, sets H = " TEX_XSTR(DIMENSION_MAX) " - D (0: use --hurst)",
               .old = "dimension"),
    TEX_REALS(struct spectral_params, anisotropy, 0, "0,1", -1e6, 1e6, 2, "ANGLE,RATIO",
              "stretch structures RATIO times along ANGLE degrees (counter-clockwise from u)"),
    TEX_REALS(struct spectral_params, band, 0, "0,1e6", 0, 1e6, 2, "LO,HI",
              "keep only frequencies LO..HI, in cycles across the longer side"),
    {0}};

/* Messages name a parameter by its row (prim.h) */
#define SPECTRAL_OPTION(field) TEX_OPTION(spectral_rows, struct spectral_params, field)

static int spectral_init(struct tex_field *f)
{
    const struct spectral_params *p = f->params;

    if (p->dimension != 0 && p->dimension < DIMENSION_MIN)
        return tex_usage_error("%s must be %d..%d, or 0 to use %s (got %g)",
                               SPECTRAL_OPTION(dimension), DIMENSION_MIN, DIMENSION_MAX,
                               SPECTRAL_OPTION(h), p->dimension);
    if (p->dimension != 0 && p->h != HURST)
        return tex_usage_error("%s and %s both set the exponent: give one",
                               SPECTRAL_OPTION(dimension), SPECTRAL_OPTION(h));
    if (p->anisotropy.n != 2 || !(p->anisotropy.v[1] > 0))
        return tex_usage_error("%s must be ANGLE,RATIO with RATIO > 0",
                               SPECTRAL_OPTION(anisotropy));
    if (p->band.n != 2 || p->band.v[0] > p->band.v[1])
        return tex_usage_error("%s must be LO,HI with LO <= HI", SPECTRAL_OPTION(band));
    return 0;
}

static int spectral_grid(const struct tex_field *f, tex_map *m)
{
    const struct spectral_params *p = f->params;
    struct tex_fbm_spec s = {p->dimension ? DIMENSION_MAX - p->dimension : p->h,
                             p->anisotropy.v[0], p->anisotropy.v[1], p->band.v[0], p->band.v[1],
                             f->seed};
    return spectral_fbm(m, &s, SPECTRAL_OPTION(band));
}

const struct tex_primitive tex_prim_spectral = {
    .name = "spectral",
    .summary = "fractional Brownian motion by spectral synthesis (amplitude f^-(H+1), random "
               "phase, inverse FFT), rescaled to [0,1]; always tiles",
    .flags = TEX_PRIM_GRID | TEX_PRIM_TILE,
    .params_size = sizeof(struct spectral_params),
    .params = spectral_rows,
    .init = spectral_init,
    .grid = spectral_grid,
};

/* The public transforms: the result carries the history of the map it came from. */
static tex_map *inherit(tex_map *r, const tex_map *from)
{
    if (r && tex_map_inherit(r, from) < 0) {
        tex_map_free(r);
        return NULL;
    }
    return r;
}

tex_map *tex_fft(const tex_map *m, enum tex_fft_output out, int hann)
{
    return inherit(fft(m, out, hann), m);
}

tex_map *tex_ifft(const tex_map *s, const struct tex_ifft_opts *o)
{
    return inherit(ifft(s, o), s);
}

tex_map *tex_sparse_convolve(const tex_map *s, int w, int h, const struct tex_sparse_spec *p)
{
    return inherit(sparse_convolve(s, w, h, p), s);
}
