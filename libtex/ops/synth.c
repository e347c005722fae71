/* synth.c - texture synthesis from an example: Lefebvre-Hoppe parallel
 * synthesis over a Gaussian stack with k-coherence candidates from FLANN.
 * The method is described in synth.h. */
#define _GNU_SOURCE /* qsort_r */
#include "ops/synth.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/fp_strict.h"
#include "base/kdtree.h"
#include "base/rng.h"
#include "ops/filter.h"
#include "ops/transform.h"

#define PCA_DIMS 10     /* dimensions of the vectors FLANN indexes */
#define PCA_SAMPLES 2048 /* sample pixels the principal axes are estimated from */
#define PCA_ITERS 24     /* subspace iterations */
#define MAX_N 15
#define KD_EPS 1 /* (1+eps)-approximate: faster than exact, the same look */
#define KD_LEAF 10 /* points a leaf of the kd-tree */
#define NONE 0xffffffffu
#define CELL 8           /* side of the sample's occurrence cells */
#define OCCURRENCE 1.0f /* weight of over-use, in units of the mean neighbourhood distance */
#define LANES 8          /* distances sum in 8 fixed lanes: vectorised, same bits anywhere */

/* One level of the sample's Gaussian stack and what the search needs of it. */
struct level {
    int h;              /* spacing of the neighbourhood's points */
    tex_map *E;         /* the stack level (the sample itself at level 0) */
    float *ne;          /* every sample pixel's weighted neighbourhood, dp floats */
    unsigned char *ok;  /* 1: a candidate (neighbourhood inside, clear of the mask) */
    int *vlist, nvalid; /* the candidates, in raster order */
    uint32_t *cset;     /* k-coherence sets, k per sample pixel: x | y << 16, NONE pads */
    float *mean, *axes; /* PCA: mean (dp) and PCA_DIMS axes (dp each) */
    int pd;             /* PCA dimensions used */
    tex_kdtree *index;
    float *pts;         /* the indexed (projected) candidates: FLANN points into them */
    tex_map *gemap;     /* guide: the blurred luma of the sample */
    const float *ge;    /* its pixels */
    int *gsorted;       /* guide: candidates sorted by ge */
};

struct synth {
    const tex_map *s;
    const struct tex_synth_opts *o;
    int W, H, nc, r, n, d, dp, k;
    float wv[MAX_N * MAX_N]; /* square roots of the Gaussian weights */
    float wsum;              /* sum of the weights times channels: the guide term's scale */
    unsigned char *masked;   /* sample pixels to fill (mask), or NULL */
    tex_map *luma;           /* the sample's luma (guide) */
    const tex_map *guide;
    /* output state at the current level */
    int ow, oh;
    int *S, *Snew;           /* sample pixel index per output pixel */
    unsigned char *fixed;    /* mask mode: pixels that keep their own position */
    float *gt;               /* guide, rank-matched, per output pixel */
    /* occurrence: how much each cell of the sample is used against its share */
    int *cellof, ncell;      /* the cell of each sample pixel */
    float *cellpen;          /* per cell: the penalty of taking a pixel there */
    double *cellshare;       /* per cell: its share of the candidates */
    float occ_scale;         /* the penalty of a cell used as often as its share */
    long done, total;        /* progress: pixel updates */
};

static inline int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* How far a candidate stays from the sample's edges: half its level's
 * neighbourhood, the rest read beyond the edge in a mirror.  The whole
 * neighbourhood inside (r h) kept the coarse levels, and with them the
 * output's histogram, off the sample's rim; none (r) broke the courses of
 * bricks. */
static inline int margin(const struct synth *y, int h)
{
    return y->r * h / 2 > y->r ? y->r * h / 2 : y->r;
}

static inline int mirror(int i, int n)
{
    return (int)tex_edge_index(i, n, TEX_EDGE_MIRROR);
}

/* A uniform number in [-1,1) from the seed, a salt and a pixel. */
static inline double hash_unit(uint64_t seed, uint64_t salt, uint64_t p)
{
    uint64_t x = tex_hash64(seed ^ tex_hash64(salt ^ tex_hash64(p)));
    return (double)(x >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/* Whole 8-float vectors: one access each, so a sanitizer build checks a
 * row in dp / 8 steps rather than 2 dp (the same sums, lane for lane). */
typedef float lanes8 __attribute__((vector_size(LANES * sizeof(float))));

static float dist2(const float *a, const float *b, int dp, float bound)
{
    lanes8 acc = {0};
    for (int i = 0; i < dp; i += LANES) {
        lanes8 x, y;
        memcpy(&x, a + i, sizeof x);
        memcpy(&y, b + i, sizeof y);
        lanes8 t = x - y;
        acc += t * t;
        if ((i & 31) == 24 || i + LANES >= dp) {
            float s = ((acc[0] + acc[1]) + (acc[2] + acc[3])) +
                      ((acc[4] + acc[5]) + (acc[6] + acc[7]));
            if (s >= bound || i + LANES >= dp)
                return s;
        }
    }
    return 0;
}

/* ---- the sample's levels ---- */

/* A one-channel copy of channel 0 (1-2 channels) or of the luma (RGB). */
static tex_map *luma_of(const tex_map *m)
{
    if (m->nc >= 3)
        return tex_map_channels(m, 1);
    tex_map *r = tex_map_new(m->w, m->h, 1);
    if (r)
        for (size_t i = 0; i < (size_t)m->w * m->h; i++)
            r->px[i] = m->px[i * m->nc];
    return r;
}

static tex_map *stack_level(const tex_map *m, int l)
{
    return l == 0 ? tex_map_clone(m) : tex_filter_gaussian(m, 0.5 * (1 << l), TEX_EDGE_MIRROR);
}

/* Which sample pixels may be candidates at spacing h: the neighbourhood
 * inside the sample and, with a mask, clear of the (blurred) masked pixels. */
static int level_valid(const struct synth *y, struct level *L, int l)
{
    int W = y->W, H = y->H, m = margin(y, L->h);
    tex_map *taint = NULL;

    if (!(L->ok = calloc((size_t)W * H, 1)))
        return tex_error("out of memory");
    if (y->masked) {
        if (!(taint = tex_map_new(W, H, 1)))
            return -1;
        for (size_t i = 0; i < (size_t)W * H; i++)
            taint->px[i] = y->masked[i];
        if (l > 0) {
            tex_map *b = tex_filter_gaussian(taint, 0.5 * (1 << l), TEX_EDGE_MIRROR);
            tex_map_free(taint);
            if (!(taint = b))
                return -1;
        }
    }
    L->nvalid = 0;
    for (int uy = m; uy < H - m; uy++)
        for (int ux = m; ux < W - m; ux++) {
            int good = 1;
            for (int dy = -y->r; taint && good && dy <= y->r; dy++) {
                const float *row = taint->px + (size_t)mirror(uy + dy * L->h, H) * W;
                for (int dx = -y->r; good && dx <= y->r; dx++)
                    good = row[mirror(ux + dx * L->h, W)] < 1e-3f;
            }
            L->ok[(size_t)uy * W + ux] = (unsigned char)good;
            L->nvalid += good;
        }
    tex_map_free(taint);
    return 0;
}

static int level_vectors(const struct synth *y, struct level *L)
{
    int W = y->W, H = y->H, nc = y->nc, r = y->r, dp = y->dp, h = L->h;
    size_t np = (size_t)W * H;

    if (np * dp > ((size_t)1 << 31))
        return tex_error("sample %dx%d is too large for a %dx%d neighbourhood", W, H, y->n, y->n);
    if (!(L->ne = malloc(np * dp * sizeof *L->ne)) || !(L->vlist = malloc(np * sizeof *L->vlist)))
        return tex_error("out of memory");
    const float *E = L->E->px;
#pragma omp parallel for schedule(static)
    for (int uy = 0; uy < H; uy++)
        for (int ux = 0; ux < W; ux++) {
            float *v = L->ne + ((size_t)uy * W + ux) * dp;
            int j = 0;
            for (int dy = -r; dy <= r; dy++) {
                const float *row = E + (size_t)mirror(uy + dy * h, H) * W * nc;
                for (int dx = -r; dx <= r; dx++, j++) {
                    const float *p = row + (size_t)mirror(ux + dx * h, W) * nc;
                    for (int c = 0; c < nc; c++)
                        v[j * nc + c] = y->wv[j] * p[c];
                }
            }
            for (j *= nc; j < dp; j++)
                v[j] = 0;
        }
    L->nvalid = 0;
    for (size_t u = 0; u < np; u++)
        if (L->ok[u])
            L->vlist[L->nvalid++] = (int)u;
    return 0;
}

/* Principal axes of the candidates' neighbourhoods: the covariance of a
 * spread of candidates, then subspace iteration (deterministic start,
 * Gram-Schmidt each step); rough axes are enough to index them. */
static int level_pca(const struct synth *y, struct level *L)
{
    int d = y->d, dp = y->dp, pd = d < PCA_DIMS ? d : PCA_DIMS;
    int ns = L->nvalid < PCA_SAMPLES ? L->nvalid : PCA_SAMPLES;
    double *mean = calloc(d, sizeof *mean), *cov = calloc((size_t)d * d, sizeof *cov);
    double *X = calloc((size_t)d * pd, sizeof *X), *Y = calloc((size_t)d * pd, sizeof *Y);
    int ok = -1;

    L->pd = pd;
    L->mean = calloc(dp, sizeof *L->mean);
    L->axes = calloc((size_t)dp * pd, sizeof *L->axes);
    if (!mean || !cov || !X || !Y || !L->mean || !L->axes) {
        tex_error("out of memory");
        goto out;
    }
    for (int s = 0; s < ns; s++) { /* every (nvalid/ns)-th candidate */
        const float *v = L->ne + (size_t)L->vlist[(size_t)s * L->nvalid / ns] * dp;
        for (int i = 0; i < d; i++)
            mean[i] += v[i];
    }
    for (int i = 0; i < d; i++)
        mean[i] /= ns;
#pragma omp parallel for schedule(dynamic, 4)
    for (int i = 0; i < d; i++)
        for (int s = 0; s < ns; s++) {
            const float *v = L->ne + (size_t)L->vlist[(size_t)s * L->nvalid / ns] * dp;
            double a = v[i] - mean[i];
            for (int j = 0; j <= i; j++)
                cov[(size_t)i * d + j] += a * (v[j] - mean[j]);
        }
    for (int i = 0; i < d; i++)
        for (int j = 0; j < i; j++)
            cov[(size_t)j * d + i] = cov[(size_t)i * d + j];
    for (int a = 0; a < pd; a++)
        for (int i = 0; i < d; i++)
            X[(size_t)a * d + i] = (i % pd == a) ? 1.0 : 0.01 * ((i * 7 + a * 13) % 11 - 5);
    for (int it = 0; it < PCA_ITERS; it++) {
        for (int a = 0; a < pd; a++) {
            double *ya = Y + (size_t)a * d, nrm = 0;
            for (int i = 0; i < d; i++) {
                double s = 0;
                for (int j = 0; j < d; j++)
                    s += cov[(size_t)i * d + j] * X[(size_t)a * d + j];
                ya[i] = s;
            }
            for (int b = 0; b < a; b++) {
                const double *yb = Y + (size_t)b * d;
                double dot = 0;
                for (int i = 0; i < d; i++)
                    dot += ya[i] * yb[i];
                for (int i = 0; i < d; i++)
                    ya[i] -= dot * yb[i];
            }
            for (int i = 0; i < d; i++)
                nrm += ya[i] * ya[i];
            nrm = sqrt(nrm);
            for (int i = 0; i < d; i++)
                ya[i] = nrm > 1e-30 ? ya[i] / nrm : (i == a);
        }
        double *sw = X;
        X = Y;
        Y = sw;
    }
    for (int i = 0; i < d; i++)
        L->mean[i] = (float)mean[i];
    for (int a = 0; a < pd; a++)
        for (int i = 0; i < d; i++)
            L->axes[(size_t)a * dp + i] = (float)X[(size_t)a * d + i];
    ok = 0;
out:
    free(mean);
    free(cov);
    free(X);
    free(Y);
    return ok;
}

static void project(const struct synth *y, const struct level *L, const float *v, float *out)
{
    for (int a = 0; a < L->pd; a++) {
        const float *ax = L->axes + (size_t)a * y->dp;
        float s = 0;
        for (int i = 0; i < y->d; i++)
            s += (v[i] - L->mean[i]) * ax[i];
        out[a] = s;
    }
}

/* The k-coherence sets: each sample pixel itself (if a candidate), then
 * its nearest candidates in PCA space more than h/2 pixels away; -1 pads. */
static int level_sets(const struct synth *y, struct level *L, float *proj)
{
    int W = y->W, H = y->H, pd = L->pd, k = y->k, h = L->h;
    int K = 2 * k + 6 < L->nvalid ? 2 * k + 6 : L->nvalid, fail = 0;
    size_t np = (size_t)W * H;
    float *pts = malloc((size_t)L->nvalid * pd * sizeof *pts);

    if (!pts || !(L->cset = malloc(np * k * sizeof *L->cset))) {
        free(pts);
        return tex_error("out of memory");
    }
    for (int i = 0; i < L->nvalid; i++)
        memcpy(pts + (size_t)i * pd, proj + (size_t)L->vlist[i] * pd, pd * sizeof *pts);
    /* the single kd-tree: no random generator (FLANN's randomised trees seed from
     * std::random_device), so the same sets on every run */
    if (!(L->index = tex_kdtree_new_f(pts, L->nvalid, pd, KD_LEAF))) {
        free(pts);
        return -1;
    }
    L->pts = pts; /* FLANN keeps a pointer to the points: they live as long as the index */
    /* Without a mask every output position is a candidate: only they need sets. */
    const int *qlist = y->masked ? NULL : L->vlist;
    long nqall = y->masked ? (long)np : L->nvalid;
    memset(L->cset, 0xff, np * k * sizeof *L->cset);
#pragma omp parallel reduction(| : fail)
    {
        enum { CHUNK = 256 };
        int *ind = malloc((size_t)CHUNK * K * sizeof *ind);
        float *dst = malloc((size_t)CHUNK * K * sizeof *dst);
        float *qb = malloc((size_t)CHUNK * pd * sizeof *qb);
#pragma omp for schedule(dynamic, 1)
        for (long c0 = 0; c0 < nqall; c0 += CHUNK) {
            int nq = nqall - c0 < CHUNK ? (int)(nqall - c0) : CHUNK;
            if (fail || !ind || !dst || !qb) {
                fail = 1;
                continue;
            }
            for (int q = 0; q < nq; q++)
                memcpy(qb + (size_t)q * pd, proj + (qlist ? qlist[c0 + q] : c0 + q) * (size_t)pd,
                       pd * sizeof *qb);
            if (tex_kdtree_knn_f(L->index, qb, nq, K, KD_EPS, 1, ind, dst) < 0) {
                fail = 1;
                continue;
            }
            for (int q = 0; q < nq; q++) {
                long u = qlist ? qlist[c0 + q] : c0 + q;
                int ux = (int)(u % W), uy = (int)(u / W), got = 0;
                uint32_t *cs = L->cset + u * k;
                if (L->ok[u])
                    cs[got++] = (uint32_t)ux | (uint32_t)uy << 16;
                for (int t = 0; t < K && got < k; t++) {
                    int i = ind[(size_t)q * K + t];
                    if (i < 0 || i >= L->nvalid)
                        continue; /* no neighbour: distances overflowed to inf (1e20) */
                    int v = L->vlist[i], vx = v % W, vy = v / W;
                    int dx = abs(vx - ux), dy = abs(vy - uy);
                    if ((dx > dy ? dx : dy) * 2 > h)
                        cs[got++] = (uint32_t)vx | (uint32_t)vy << 16;
                }
            }
        }
        free(qb);
        free(ind);
        free(dst);
    }
    if (fail)
        return tex_error("FLANN's nearest-neighbour search failed (out of memory?)");
    return 0;
}

/* Guide: the sample's luma blurred to the level's scale, and the
 * candidates sorted by it (ties by position). */
static int by_key(const void *a, const void *b, void *key)
{
    int i = *(const int *)a, j = *(const int *)b;
    float x = ((const float *)key)[i], z = ((const float *)key)[j];
    return x < z ? -1 : x > z ? 1 : (i > j) - (i < j);
}

static int level_guide(const struct synth *y, struct level *L)
{
    double sigma = 0.5 * y->r * L->h;
    tex_map *b = sigma < 0.5 ? tex_map_clone(y->luma)
                              : tex_filter_gaussian(y->luma, sigma, TEX_EDGE_MIRROR);
    if (!b)
        return -1;
    L->gemap = b;
    L->ge = b->px;
    if (!(L->gsorted = malloc((size_t)L->nvalid * sizeof *L->gsorted)))
        return tex_error("out of memory");
    memcpy(L->gsorted, L->vlist, (size_t)L->nvalid * sizeof *L->gsorted);
    qsort_r(L->gsorted, L->nvalid, sizeof *L->gsorted, by_key, (void *)L->ge);
    return 0;
}

static void level_free(struct level *L)
{
    tex_kdtree_free(L->index);
    tex_map_free(L->E);
    free(L->ne);
    free(L->ok);
    free(L->vlist);
    free(L->cset);
    free(L->mean);
    free(L->axes);
    free(L->pts);
    tex_map_free(L->gemap);
    free(L->gsorted);
    memset(L, 0, sizeof *L);
}

/* Everything level l needs; L->ok is set already (level_valid). */
static int level_build(const struct synth *y, struct level *L, int l)
{
    size_t np = (size_t)y->W * y->H;
    float *proj = NULL;
    int rc = -1;

    if (!(L->E = stack_level(y->s, l)) || level_vectors(y, L) < 0)
        return -1;
    if (y->guide && level_guide(y, L) < 0)
        return -1;
    if (y->o->search == TEX_SYNTH_EXHAUSTIVE)
        return 0; /* every candidate is tried: no sets, no tree */
    if (level_pca(y, L) < 0)
        return -1;
    if (!(proj = malloc(np * L->pd * sizeof *proj)))
        return tex_error("out of memory");
#pragma omp parallel for schedule(static)
    for (long u = 0; u < (long)np; u++)
        project(y, L, L->ne + u * y->dp, proj + u * L->pd);
    rc = level_sets(y, L, proj);
    free(proj);
    return rc;
}

/* ---- the output ---- */

/* The sample position output pixel (x,y) holds, extended beyond the edges
 * of an output that does not tile by continuing its border's positions. */
static void pos_at(const struct synth *y, int h, int x, int yy, int *ux, int *uy)
{
    int qx, qy, u;
    if (y->o->tile) { /* a torus: the neighbour is on the other side */
        qx = (int)tex_edge_index(x, y->ow, TEX_EDGE_WRAP);
        qy = (int)tex_edge_index(yy, y->oh, TEX_EDGE_WRAP);
        u = y->S[(size_t)qy * y->ow + qx];
        *ux = u % y->W;
        *uy = u / y->W;
        return;
    }
    qx = clampi(x, 0, y->ow - 1);
    qy = clampi(yy, 0, y->oh - 1);
    u = y->S[(size_t)qy * y->ow + qx];
    *ux = clampi(u % y->W + (x - qx) * h, 0, y->W - 1);
    *uy = clampi(u / y->W + (yy - qy) * h, 0, y->H - 1);
}

/* The output's neighbourhood of (x,y): the stack's values at the positions
 * its neighbours hold, weighted like the sample's. */
static void gather(const struct synth *y, const struct level *L, int x, int yy, float *v)
{
    int j = 0, nc = y->nc, r = y->r;
    const float *E = L->E->px;
    if (x >= r && yy >= r && x + r < y->ow && yy + r < y->oh) { /* inside: no edge rule */
        for (int dy = -r; dy <= r; dy++) {
            const int *row = y->S + (size_t)(yy + dy) * y->ow + x;
            for (int dx = -r; dx <= r; dx++, j++) {
                const float *p = E + (size_t)row[dx] * nc;
                for (int c = 0; c < nc; c++)
                    v[j * nc + c] = y->wv[j] * p[c];
            }
        }
    } else {
        for (int dy = -r; dy <= r; dy++)
            for (int dx = -r; dx <= r; dx++, j++) {
                int ux, uy;
                pos_at(y, L->h, x + dx, yy + dy, &ux, &uy);
                const float *p = tex_map_px(L->E, ux, uy);
                for (int c = 0; c < nc; c++)
                    v[j * nc + c] = y->wv[j] * p[c];
            }
    }
    for (j *= nc; j < y->dp; j++)
        v[j] = 0;
}

/* A pixel's candidates, without repeats: seen[u] holds the last pixel
 * that listed u (each thread has its own). */
struct cands {
    int n, max, *u;
    int *seen;
};

static inline void cand_add(struct cands *c, const struct level *L, int u, int p)
{
    if (u < 0 || !L->ok[u] || c->seen[u] == p)
        return;
    c->seen[u] = p;
    if (c->n < c->max)
        c->u[c->n++] = u;
}

/* The best candidate for output pixel (x,y) at level l. */
static int correct_pixel(const struct synth *y, const struct level *L, int l, int top, int x,
                         int yy, float *v, struct cands *c, float *q, int *ind, float *dst)
{
    int W = y->W, H = y->H, h = L->h, p = yy * y->ow + x;
    const int *cand;
    int ncand;

    gather(y, L, x, yy, v);
    c->n = 0;
    if (y->o->search == TEX_SYNTH_EXHAUSTIVE) {
        cand = L->vlist;
        ncand = L->nvalid;
    } else {
        cand_add(c, L, y->S[p], p);
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int qx = x + dx, qy = yy + dy;
                if (!y->o->tile && (qx < 0 || qy < 0 || qx >= y->ow || qy >= y->oh))
                    continue;
                qx = (int)tex_edge_index(qx, y->ow, TEX_EDGE_WRAP);
                qy = (int)tex_edge_index(qy, y->oh, TEX_EDGE_WRAP);
                const uint32_t *cs = L->cset + (size_t)y->S[(size_t)qy * y->ow + qx] * y->k;
                for (int t = 0; t < y->k && cs[t] != NONE; t++) {
                    int ux = (int)(cs[t] & 0xffff) - dx * h, uy = (int)(cs[t] >> 16) - dy * h;
                    if (ux >= 0 && uy >= 0 && ux < W && uy < H)
                        cand_add(c, L, uy * W + ux, p);
                }
            }
        if (top) { /* the coarsest level's first pass: FLANN proposes too */
            int K = y->k < L->nvalid ? y->k : L->nvalid;
            project(y, L, v, q);
            if (tex_kdtree_knn_f(L->index, q, 1, K, KD_EPS, 1, ind, dst) == 0)
                for (int t = 0; t < K; t++)
                    if (ind[t] >= 0 && ind[t] < L->nvalid) /* as in the candidate sets */
                        cand_add(c, L, L->vlist[ind[t]], p);
        }
        if (y->gt) { /* two sample positions of about the guide's luma */
            const float *key = L->ge;
            int lo = 0, hi = L->nvalid;
            while (lo < hi) {
                int mid = (lo + hi) / 2;
                if (key[L->gsorted[mid]] < y->gt[p])
                    lo = mid + 1;
                else
                    hi = mid;
            }
            int spread = L->nvalid / 64 + 1;
            for (int t = 0; t < 2; t++) {
                double z = hash_unit(y->o->seed, 0x9a1d0000u + l * 16 + t, (uint64_t)p);
                cand_add(c, L, L->gsorted[clampi(lo + (int)(z * spread), 0, L->nvalid - 1)], p);
            }
        }
        cand = c->u;
        ncand = c->n;
    }
    int best = -1;
    float bestd = INFINITY;
    for (int i = 0; i < ncand; i++) {
        int u = cand[i];
        if (i + 4 < ncand) { /* the rows are scattered over the table: fetch ahead */
            const char *next = (const char *)(L->ne + (size_t)cand[i + 4] * y->dp);
            for (int b = 0; b < y->dp * (int)sizeof(float); b += 64)
                __builtin_prefetch(next + b);
        }
        float d = dist2(v, L->ne + (size_t)u * y->dp, y->dp, bestd) + y->cellpen[y->cellof[u]];
        if (y->gt) {
            float g = y->gt[p] - L->ge[u];
            d += (float)y->o->guide_weight * y->wsum * g * g;
        }
        if (d < bestd) {
            bestd = d;
            best = u;
        }
    }
    if (best < 0) /* no candidate fits: any valid position, chosen by the seed */
        best = L->vlist[tex_hash64(y->o->seed ^ tex_hash64(0xfa11ULL + p + ((uint64_t)l << 40))) %
                        (uint64_t)L->nvalid];
    return best;
}

/* The occurrence penalty of each cell for the coming pass (after Kaspar
 * et al. 2015): the cell's count among the output's positions over its
 * share, times the level's mean neighbourhood distance, so that no part
 * of the sample is copied much more often than the rest. */
static void occurrence(struct synth *y, const struct level *L)
{
    size_t np = (size_t)y->ow * y->oh, nfree = 0;
    double *cnt = calloc(y->ncell, sizeof *cnt);

    if (!cnt) { /* no penalty this pass: still deterministic */
        memset(y->cellpen, 0, y->ncell * sizeof *y->cellpen);
        return;
    }
    for (size_t p = 0; p < np; p++)
        if (!y->fixed || !y->fixed[p]) {
            cnt[y->cellof[y->S[p]]] += 1;
            nfree++;
        }
    for (int c = 0; c < y->ncell; c++)
        y->cellpen[c] = y->cellshare[c] > 0
                            ? (float)(y->occ_scale * cnt[c] / (y->cellshare[c] * nfree))
                            : 0;
    free(cnt);
    (void)L;
}

/* The cells' shares of the candidates and the penalty's scale at a level. */
static int occurrence_setup(struct synth *y, const struct level *L)
{
    size_t np = (size_t)y->W * y->H;
    int cw = (y->W + CELL - 1) / CELL;
    double var = 0;

    y->ncell = cw * ((y->H + CELL - 1) / CELL);
    if (!y->cellof && !(y->cellof = malloc(np * sizeof *y->cellof)))
        return tex_error("out of memory");
    free(y->cellpen);
    free(y->cellshare);
    y->cellpen = calloc(y->ncell, sizeof *y->cellpen);
    y->cellshare = calloc(y->ncell, sizeof *y->cellshare);
    if (!y->cellpen || !y->cellshare)
        return tex_error("out of memory");
    for (size_t u = 0; u < np; u++)
        y->cellof[u] = (int)(u / y->W / CELL * cw + u % y->W / CELL);
    for (int i = 0; i < L->nvalid; i++)
        y->cellshare[y->cellof[L->vlist[i]]] += 1.0 / L->nvalid;
    /* the mean squared distance between two random candidates' neighbourhoods
     * is twice the sum of the per-value variances (each weighted) */
    for (int c = 0; c < y->nc; c++) {
        struct tex_stats st;
        tex_map_stats(L->E, c, &st);
        var += st.stddev * st.stddev;
    }
    y->occ_scale = OCCURRENCE * (float)(2 * var / y->nc) * y->wsum;
    return 0;
}

static int correct(struct synth *y, const struct level *L, int l, int top)
{
    int fail = 0;
    for (int pass = 0; pass < y->o->passes; pass++)
        for (int sub = 0; sub < 4; sub++) {
            if (sub == 0)
                occurrence(y, L);
            int sx = sub & 1, sy = sub >> 1;
#pragma omp parallel reduction(| : fail)
            {
                struct cands c = {0, 9 * y->k + 8 + y->k, NULL, NULL};
                float *v = malloc(y->dp * sizeof *v), q[PCA_DIMS];
                float *dst = malloc(y->k * sizeof *dst);
                int *ind = malloc(y->k * sizeof *ind);
                c.u = malloc(c.max * sizeof *c.u);
                c.seen = malloc((size_t)y->W * y->H * sizeof *c.seen);
                if (c.seen)
                    memset(c.seen, 0xff, (size_t)y->W * y->H * sizeof *c.seen);
                if (!v || !c.u || !c.seen || !dst || !ind)
                    fail = 1;
#pragma omp for schedule(dynamic, 4)
                for (int yy = sy; yy < y->oh; yy += 2)
                    for (int x = sx; x < y->ow && !fail; x += 2) {
                        size_t p = (size_t)yy * y->ow + x;
                        y->Snew[p] = y->fixed && y->fixed[p]
                                         ? y->S[p]
                                         : correct_pixel(y, L, l, top && pass == 0, x, yy, v, &c, q,
                                                         ind, dst);
                    }
                free(v);
                free(c.u);
                free(c.seen);
                free(dst);
                free(ind);
            }
            if (fail)
                return tex_error("out of memory");
            for (int yy = sy; yy < y->oh; yy += 2)
                for (int x = sx; x < y->ow; x += 2)
                    y->S[(size_t)yy * y->ow + x] = y->Snew[(size_t)yy * y->ow + x];
            y->done += (long)((y->ow - sx + 1) / 2) * ((y->oh - sy + 1) / 2);
            if (y->o->progress)
                y->o->progress(y->done, y->total, y->o->progress_arg);
        }
    return 0;
}

/* Output size at level l: ceil(w / 2^l). */
static int level_side(int w, int l)
{
    return (int)(((long)w + (1L << l) - 1) >> l);
}

/* Mask mode: the output pixels of level l whose whole footprint is known. */
static void fixed_pixels(struct synth *y, int h)
{
    for (int py = 0; py < y->oh; py++)
        for (int px = 0; px < y->ow; px++) {
            int f = 1;
            for (int fy = py * h; f && fy < (py + 1) * h && fy < y->H; fy++)
                for (int fx = px * h; f && fx < (px + 1) * h && fx < y->W; fx++)
                    f = !y->masked[(size_t)fy * y->W + fx];
            y->fixed[(size_t)py * y->ow + px] = (unsigned char)f;
        }
}

/* The coarsest level starts as a quilt (Efros and Freeman 2001): blocks
 * of B x B pixels, each a window of the sample, laid in raster order; each
 * window's origin is drawn, by the seed, among those whose first rows and
 * columns best continue the blocks placed above and to the left (and, when
 * the output tiles, below and to the right at the far edges).  Regular
 * samples keep their period across blocks; the passes mend the rest. */
struct quilt {
    int h, m, B, ov, nbx, nby, step, nox, noy;
};

/* The squared difference between window origin (ox,oy) at output pixel
 * (x,y) of its block and the continuation of placed neighbour q, shifted
 * by (sx,sy) level pixels. */
static float quilt_term(const struct synth *y, const struct level *L, const struct quilt *Q, int ox,
                        int oy, int bx0, int by0, int x, int yy, int q, int sx, int sy)
{
    int u = y->S[q], ux = clampi(u % y->W + sx * Q->h, 0, y->W - 1);
    int uy = clampi(u / y->W + sy * Q->h, 0, y->H - 1);
    const float *a = tex_map_px(L->E, ox + (x - bx0) * Q->h, oy + (yy - by0) * Q->h);
    const float *b = tex_map_px(L->E, ux, uy);
    float s = 0;
    for (int c = 0; c < y->nc; c++)
        s += (a[c] - b[c]) * (a[c] - b[c]);
    return s;
}

static float quilt_cost(const struct synth *y, const struct level *L, const struct quilt *Q, int bx,
                        int by, int ox, int oy)
{
    int x0 = bx * Q->B, y0 = by * Q->B, x1 = x0 + Q->B, y1 = y0 + Q->B, ow = y->ow;
    float cost = 0;
    x1 = x1 < y->ow ? x1 : y->ow;
    y1 = y1 < y->oh ? y1 : y->oh;
    for (int yy = y0; yy < y1; yy++)
        for (int i = 0; i < Q->ov && x0 + i < x1; i++) {
            if (bx > 0) /* the block to the left */
                cost += quilt_term(y, L, Q, ox, oy, x0, y0, x0 + i, yy, yy * ow + x0 - 1, i + 1, 0);
            if (y->o->tile && bx == Q->nbx - 1 && bx > 0) /* the first block, to the right */
                cost += quilt_term(y, L, Q, ox, oy, x0, y0, x1 - 1 - i, yy, yy * ow, -i - 1, 0);
        }
    for (int x = x0; x < x1; x++)
        for (int i = 0; i < Q->ov && y0 + i < y1; i++) {
            if (by > 0)
                cost += quilt_term(y, L, Q, ox, oy, x0, y0, x, y0 + i, (y0 - 1) * ow + x, 0, i + 1);
            if (y->o->tile && by == Q->nby - 1 && by > 0)
                cost += quilt_term(y, L, Q, ox, oy, x0, y0, x, y1 - 1 - i, x, 0, -i - 1);
        }
    return cost;
}

static int start_quilt(struct synth *y, const struct level *L)
{
    struct quilt Q;
    float *cost;
    int ncand, ncx;

    Q.h = L->h;
    Q.m = margin(y, Q.h);
    Q.B = (y->W - 2 * Q.m) / (2 * Q.h);
    if ((y->H - 2 * Q.m) / (2 * Q.h) < Q.B)
        Q.B = (y->H - 2 * Q.m) / (2 * Q.h);
    Q.B = Q.B < 1 ? 1 : Q.B;
    Q.ov = Q.B / 2 < y->r ? (Q.B + 1) / 2 : y->r;
    Q.nbx = (y->ow + Q.B - 1) / Q.B;
    Q.nby = (y->oh + Q.B - 1) / Q.B;
    Q.nox = y->W - 2 * Q.m - (Q.B - 1) * Q.h; /* origins whose window fits */
    Q.noy = y->H - 2 * Q.m - (Q.B - 1) * Q.h;
    Q.step = 1;
    while ((long)((Q.nox + Q.step - 1) / Q.step) * ((Q.noy + Q.step - 1) / Q.step) > 1024)
        Q.step++;
    ncx = (Q.nox + Q.step - 1) / Q.step;
    ncand = ncx * ((Q.noy + Q.step - 1) / Q.step);
    if (!(cost = malloc(ncand * sizeof *cost)))
        return tex_error("out of memory");
    for (int by = 0; by < Q.nby; by++)
        for (int bx = 0; bx < Q.nbx; bx++) {
            float best = INFINITY;
            int nc = 0, pick, i = 0;
            /* serial: a parallel region per block cost more than it saved */
            for (int c = 0; c < ncand; c++) {
                int cx = c % ncx, cy = c / ncx;
                cost[c] = quilt_cost(y, L, &Q, bx, by, Q.m + cx * Q.step, Q.m + cy * Q.step);
            }
            for (int c = 0; c < ncand; c++)
                best = cost[c] < best ? cost[c] : best;
            for (int c = 0; c < ncand; c++)
                nc += cost[c] <= best * 1.1f + 1e-6f;
            /* costs all NaN (inf - inf, from values near FLT_MAX): any origin will do */
            int any = nc == 0;
            uint64_t z = tex_hash64(y->o->seed ^ tex_hash64(0x5747ULL + (uint64_t)by * Q.nbx + bx));
            pick = (int)(z % (uint64_t)(any ? ncand : nc));
            for (int c = 0; c < ncand; c++)
                if ((any || cost[c] <= best * 1.1f + 1e-6f) && i++ == pick) {
                    int cx = c % ncx, cy = c / ncx;
                    int ox = Q.m + cx * Q.step, oy = Q.m + cy * Q.step;
                    for (int yy = by * Q.B; yy < (by + 1) * Q.B && yy < y->oh; yy++)
                        for (int x = bx * Q.B; x < (bx + 1) * Q.B && x < y->ow; x++)
                            y->S[(size_t)yy * y->ow + x] =
                                (oy + (yy - by * Q.B) * Q.h) * y->W + ox + (x - bx * Q.B) * Q.h;
                    break;
                }
        }
    free(cost);
    return 0;
}

/* Start level l: random candidates at the coarsest level (of a mask), else the parent's
 * position plus h times the child's offset, jittered. */
static void start_level(struct synth *y, const struct level *L, int l, const int *parent, int pw)
{
    int h = L->h, m = margin(y, h);
#pragma omp parallel for schedule(static)
    for (int py = 0; py < y->oh; py++)
        for (int px = 0; px < y->ow; px++) {
            size_t p = (size_t)py * y->ow + px;
            int ux, uy;
            if (y->fixed && y->fixed[p]) {
                ux = px * h < y->W ? px * h : y->W - 1;
                uy = py * h < y->H ? py * h : y->H - 1;
            } else if (!parent) { /* the coarsest level of a mask: any candidate */
                y->S[p] = L->vlist[tex_hash64(y->o->seed ^ tex_hash64(0x5747ULL + p)) %
                                   (uint64_t)L->nvalid];
                continue;
            } else {
                int u = parent[(size_t)(py >> 1) * pw + (px >> 1)];
                double a = 2 * y->o->randomness * h;
                ux = u % y->W + h * (px & 1) +
                     (int)floor(a * hash_unit(y->o->seed, 0x117e0000u + 2 * l, p) + 0.5);
                uy = u / y->W + h * (py & 1) +
                     (int)floor(a * hash_unit(y->o->seed, 0x117e0001u + 2 * l, p) + 0.5);
                ux = clampi(ux, m, y->W - 1 - m);
                uy = clampi(uy, m, y->H - 1 - m);
            }
            y->S[p] = uy * y->W + ux;
        }
}

/* The guide at level l: its luma averaged over each pixel's footprint,
 * then given the distribution of the sample's blurred luma by rank. */
static int guide_targets(struct synth *y, const struct level *L, int h)
{
    size_t np = (size_t)y->ow * y->oh;
    float *raw = malloc(np * sizeof *raw);
    int *order = malloc(np * sizeof *order);
    tex_map *g = luma_of(y->guide);

    if (!raw || !order || !g) {
        free(raw);
        free(order);
        tex_map_free(g);
        return tex_error("out of memory");
    }
    for (int py = 0; py < y->oh; py++)
        for (int px = 0; px < y->ow; px++) {
            double s = 0;
            int n = 0;
            for (int fy = py * h; fy < (py + 1) * h && fy < g->h; fy++)
                for (int fx = px * h; fx < (px + 1) * h && fx < g->w; fx++, n++)
                    s += g->px[(size_t)fy * g->w + fx];
            raw[(size_t)py * y->ow + px] = (float)(s / n);
        }
    for (size_t i = 0; i < np; i++)
        order[i] = (int)i;
    qsort_r(order, np, sizeof *order, by_key, raw);
    for (size_t i = 0; i < np; i++)
        y->gt[order[i]] = L->ge[L->gsorted[i * L->nvalid / np]];
    free(raw);
    free(order);
    tex_map_free(g);
    return 0;
}

static int check_opts(const struct tex_synth_opts *o)
{
    if (o->neighbourhood < 3 || o->neighbourhood > MAX_N || !(o->neighbourhood & 1))
        return tex_usage_error("--neighbourhood must be odd, 3..%d (got %d)", MAX_N,
                               o->neighbourhood);
    if (o->levels < 1 || o->levels > 10)
        return tex_usage_error("--levels must be 1..10 (got %d)", o->levels);
    if (o->k < 1 || o->k > 16)
        return tex_usage_error("--candidates must be 1..16 (got %d)", o->k);
    if (o->passes < 1 || o->passes > 8)
        return tex_usage_error("--passes must be 1..8 (got %d)", o->passes);
    if (!(o->randomness >= 0 && o->randomness <= 1))
        return tex_usage_error("--randomness must be 0..1 (got %g)", o->randomness);
    if (!(o->guide_weight >= 0 && o->guide_weight <= 100))
        return tex_usage_error("--guide-weight must be 0..100 (got %g)", o->guide_weight);
    return 0;
}

static int check_maps(const tex_map *s, int w, int h, const struct tex_synth_opts *o,
                      const tex_map *guide, const tex_map *mask)
{
    int n = o->neighbourhood;
    if (s->w < n || s->h < n)
        return tex_error("the sample is %dx%d, smaller than the %dx%d neighbourhood", s->w, s->h,
                         n, n);
    for (size_t i = 0; i < tex_map_samples(s); i++)
        if (!isfinite(s->px[i]))
            return tex_error("the sample has %s at pixel (%zu,%zu)",
                             isnan(s->px[i]) ? "NaN" : "an infinity", i / s->nc % s->w,
                             i / s->nc / s->w);
    if (mask && (mask->w != s->w || mask->h != s->h))
        return tex_usage_error("the mask is %dx%d; it must be the sample's size, %dx%d", mask->w,
                               mask->h, s->w, s->h);
    if (w < 1 || h < 1 || (long long)w * h > TEX_SYNTH_MAX_PIXELS)
        return tex_usage_error("the output %dx%d is over the synthesis limit of %lld pixels", w, h,
                               TEX_SYNTH_MAX_PIXELS);
    if (guide && (guide->w != w || guide->h != h))
        return tex_usage_error("the guide is %dx%d; it must be the output's size, %dx%d",
                               guide->w, guide->h, w, h);
    return 0;
}

static int setup(struct synth *y, const tex_map *s, const struct tex_synth_opts *o,
                 const tex_map *guide, const tex_map *mask)
{
    double sigma;

    memset(y, 0, sizeof *y);
    y->s = s;
    y->o = o;
    y->W = s->w;
    y->H = s->h;
    y->nc = s->nc;
    y->n = o->neighbourhood;
    y->r = y->n / 2;
    y->d = y->n * y->n * y->nc;
    y->dp = (y->d + LANES - 1) / LANES * LANES;
    y->k = o->k;
    y->guide = guide;
    sigma = y->r; /* gentle Gaussian falloff: the centre counts most */
    for (int dy = -y->r, j = 0; dy <= y->r; dy++)
        for (int dx = -y->r; dx <= y->r; dx++, j++) {
            double wt = exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
            y->wv[j] = (float)sqrt(wt);
            y->wsum += (float)(wt * y->nc);
        }
    if (mask) {
        if (!(y->masked = malloc((size_t)y->W * y->H)))
            return tex_error("out of memory");
        for (size_t i = 0; i < (size_t)y->W * y->H; i++)
            y->masked[i] = mask->px[i * mask->nc] > 0.5f;
    }
    if (guide && !(y->luma = luma_of(s)))
        return -1;
    return 0;
}

/* The levels' candidates; returns how many levels fit (0 after an error). */
static int count_levels(struct synth *y, struct level *lv)
{
    int L = 0;
    for (int l = 0; l < y->o->levels; l++) {
        lv[l].h = 1 << l;
        if (level_valid(y, &lv[l], l) < 0)
            return 0;
        if (lv[l].nvalid == 0)
            break;
        L = l + 1;
    }
    if (L == 0)
        tex_error("no %dx%d neighbourhood of the %dx%d sample lies inside it%s", y->n, y->n, y->W,
                  y->H, y->masked ? " and clear of the mask" : "");
    return L;
}

static tex_map *result(const struct synth *y, int w, int h)
{
    tex_map *m = tex_map_new(w, h, y->nc);
    if (!m)
        return NULL;
    for (size_t p = 0; p < (size_t)w * h; p++)
        memcpy(m->px + p * y->nc, y->s->px + (size_t)y->S[p] * y->nc, y->nc * sizeof *m->px);
    m->subregions = y->s->subregions;
    if (tex_map_inherit(m, y->s) < 0) {
        tex_map_free(m);
        return NULL;
    }
    return m;
}

tex_map *tex_synth(const tex_map *s, int w, int h, const struct tex_synth_opts *o,
                   const tex_map *guide, const tex_map *mask)
{
    struct synth y;
    struct level lv[10];
    tex_map *out = NULL;
    int *parent = NULL, pw = 0, L;

    if (mask) {
        w = s->w;
        h = s->h;
    }
    if (check_opts(o) < 0 || check_maps(s, w, h, o, guide, mask) < 0)
        return NULL;
    memset(lv, 0, sizeof lv);
    if (setup(&y, s, o, guide, mask) < 0 || !(L = count_levels(&y, lv)))
        goto out;
    for (int l = 0; l < L; l++)
        y.total += (long)level_side(w, l) * level_side(h, l) * o->passes;
    for (int l = L - 1; l >= 0; l--) {
        struct level *V = lv + l;
        size_t np;
        y.ow = level_side(w, l);
        y.oh = level_side(h, l);
        np = (size_t)y.ow * y.oh;
        if (level_build(&y, V, l) < 0)
            goto out;
        free(y.Snew);
        free(y.fixed);
        free(y.gt);
        y.fixed = NULL;
        y.gt = NULL;
        if (!(y.S = malloc(np * sizeof *y.S)) || !(y.Snew = malloc(np * sizeof *y.Snew)) ||
            (mask && !(y.fixed = malloc(np))) || (guide && !(y.gt = malloc(np * sizeof *y.gt)))) {
            tex_error("out of memory");
            goto out;
        }
        if (mask)
            fixed_pixels(&y, V->h);
        if (!parent && !mask) {
            if (start_quilt(&y, V) < 0)
                goto out;
        } else
            start_level(&y, V, l, parent, pw);
        free(parent);
        parent = NULL;
        if ((guide && guide_targets(&y, V, V->h) < 0) || occurrence_setup(&y, V) < 0 ||
            correct(&y, V, l, l == L - 1) < 0)
            goto out;
        level_free(V);
        parent = y.S;
        pw = y.ow;
        y.S = NULL;
    }
    y.S = parent;
    parent = NULL;
    out = result(&y, w, h);
out:
    for (int l = 0; l < 10; l++)
        level_free(lv + l);
    free(parent);
    free(y.S);
    free(y.Snew);
    free(y.fixed);
    free(y.gt);
    free(y.masked);
    free(y.cellof);
    free(y.cellpen);
    free(y.cellshare);
    tex_map_free(y.luma);
    return out;
}
