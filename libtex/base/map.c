/* map.c - allocation and metadata of texture maps */
#include <ctype.h>
#include <errno.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <pthread.h>
#include <sys/mman.h>

#include "base/error.h"
#include "base/map.h"
#include "base/simd.h"
#include "base/x86/stats_x86.h"

_Static_assert(TEX_MAP_MAX_SIDE == 65536 && TEX_MAP_MAX_SAMPLES == 1ULL << 30,
               "TEX_MAP_SIZE_RULE and the message below say these limits");

int tex_map_check_sides(long long w, long long h, long long nc)
{
    if (w < 1 || w > TEX_MAP_MAX_SIDE || h < 1 || h > TEX_MAP_MAX_SIDE)
        return tex_usage_error("size %lldx%lld is out of range: " TEX_MAP_SIZE_RULE, w, h);
    if (nc < 1 || nc > TEX_MAP_MAX_CHANNELS)
        return tex_usage_error("%lld channels is out of range: 1..%d", nc, TEX_MAP_MAX_CHANNELS);
    return 0;
}

int tex_map_check_size(long long w, long long h, long long nc)
{
    if (tex_map_check_sides(w, h, nc) < 0)
        return -1;
    /* Each factor is at most 2^16, so the product fits in 64 bits. */
    if ((unsigned long long)w * h * nc > TEX_MAP_MAX_SAMPLES)
        return tex_usage_error("size %lldx%lldx%lld is too large to hold whole: at most 2^30 "
                               "samples (4 GiB of float); only streaming tools take it",
                               w, h, nc);
    return 0;
}

/* Fresh zeroed pages, *bytes of them rounded up to whole 2 MiB pages on a 2 MiB boundary, in
 * huge pages where the kernel gives them: in 4 KiB pages a render spent much of its time in
 * page faults. NULL if the kernel has no memory. */
static void *mapped_pages(size_t *bytes)
{
    const size_t huge = (size_t)2 << 20;
    size_t n = (*bytes + huge - 1) / huge * huge;
    char *p = mmap(NULL, n + huge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED)
        return NULL;
    size_t head = (huge - (uintptr_t)p % huge) % huge;
    if (head)
        munmap(p, head);
    munmap(p + head + n, huge - head); /* page-aligned, as mmap's p is */
    madvise(p + head, n, MADV_HUGEPAGE);
    *bytes = n;
    return p + head;
}

/* Mappings freed, kept for the next of their size: a band op frees its band's maps and makes
 * maps of the same sizes for the next band, and fresh pages each time were a third of
 * t_palette's CPU in a pipe, zeroed by the kernel (doc/performance.md). At most KEEP_SLOTS of
 * at most KEEP_MAX bytes each and KEEP_ALL in all, so a tool holds little more than a band's
 * maps beyond what it uses. */
enum { KEEP_SLOTS = 4 };
#define KEEP_MAX ((size_t)64 << 20)
#define KEEP_ALL ((size_t)128 << 20)
static struct {
    void *p;
    size_t n;
} kept[KEEP_SLOTS];
static size_t kept_all;
static pthread_mutex_t kept_lock = PTHREAD_MUTEX_INITIALIZER;

/* The smallest kept mapping of n to 2n bytes, taken out (*n its size); NULL if none. Up to 2n:
 * the last band's maps, shorter, reuse the others' (a mapping of its own made the blur's peak
 * RSS 28 MB larger), and a buffer much smaller (the writer's band) leaves them to the maps. */
static void *kept_take(size_t *n)
{
    int best = -1;

    pthread_mutex_lock(&kept_lock);
    for (int i = 0; i < KEEP_SLOTS; i++)
        if (kept[i].p && kept[i].n >= *n && kept[i].n / 2 <= *n &&
            (best < 0 || kept[i].n < kept[best].n))
            best = i;
    void *p = best < 0 ? NULL : kept[best].p;
    if (p) {
        *n = kept[best].n;
        kept_all -= *n;
        kept[best].p = NULL;
    }
    pthread_mutex_unlock(&kept_lock);
    return p;
}

/* 1 if p (n bytes) is kept, 0 if it is the caller's to unmap */
static int kept_give(void *p, size_t n)
{
    int given = 0;

    if (n > KEEP_MAX)
        return 0;
    pthread_mutex_lock(&kept_lock);
    for (int i = 0; i < KEEP_SLOTS && !given && kept_all + n <= KEEP_ALL; i++)
        if (!kept[i].p)
            kept[i].p = p, kept[i].n = n, kept_all += n, given = 1;
    pthread_mutex_unlock(&kept_lock);
    return given;
}

/* tex_pages_new's memory, zeroed or (zero 0) as a kept mapping left it */
static void *pages_new(size_t bytes, size_t min, size_t *mapped, int zero)
{
    const size_t huge = (size_t)2 << 20;
    void *p;

    *mapped = 0;
    if (bytes && bytes >= min) {
        size_t n = (bytes + huge - 1) / huge * huge;
        if ((p = kept_take(&n))) {
            if (zero)
                memset(p, 0, bytes);
        } else if (!(p = mapped_pages(&n))) {
            return NULL;
        }
        *mapped = n;
        return p;
    }
    /* aligned_alloc wants a multiple of the alignment */
    if ((p = aligned_alloc(64, (bytes + 63) & ~(size_t)63)) && zero)
        memset(p, 0, bytes);
    return p;
}

void tex_pages_touch(void *p, size_t mapped)
{
    if (!mapped)
        return; /* the heap's: memset already */
#ifdef MADV_POPULATE_WRITE
    if (!madvise(p, mapped, MADV_POPULATE_WRITE))
        return;
#endif
    for (size_t i = 0; i < mapped; i += 4096) /* a kernel before 5.14 */
        ((volatile char *)p)[i] = 0;
}

void *tex_pages_new(size_t bytes, size_t min, size_t *mapped)
{
    return pages_new(bytes, min, mapped, 1);
}

void tex_pages_free(void *p, size_t mapped)
{
    if (mapped && !kept_give(p, mapped))
        munmap(p, mapped);
    else if (!mapped)
        free(p);
}

void tex_keep_heap(void)
{
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

static tex_map *map_new(int w, int h, int nc, int zero)
{
    tex_map *m;
    size_t bytes;

    if (tex_map_check_size(w, h, nc) < 0)
        return NULL;
    if (!(m = calloc(1, sizeof *m))) {
        tex_error("out of memory");
        return NULL;
    }
    bytes = (size_t)w * h * nc * sizeof *m->px;
    /* from 1 MiB, pages of their own: fresh ones come zeroed, no pass over a map the caller
     * will fill */
    if (!(m->px = pages_new(bytes, 1 << 20, &m->mapped, zero))) {
        free(m);
        tex_error("out of memory for a %dx%dx%d map", w, h, nc);
        return NULL;
    }
    m->w = w;
    m->h = h;
    m->nc = nc;
    return m;
}

tex_map *tex_map_new(int w, int h, int nc)
{
    return map_new(w, h, nc, 1);
}

tex_map *tex_map_new_unset(int w, int h, int nc)
{
    return map_new(w, h, nc, 0);
}

void tex_map_free(tex_map *m)
{
    if (!m)
        return;
    tex_pages_free(m->px, m->mapped);
    free(m->history);
    free(m);
}

tex_map *tex_map_clone(const tex_map *m)
{
    tex_map *c = tex_map_new(m->w, m->h, m->nc);

    if (!c)
        return NULL;
    memcpy(c->px, m->px, tex_map_samples(m) * sizeof *m->px);
    c->subregions = m->subregions;
    tex_map_inherit_place(c, m);
    if (m->history && tex_map_set_history(c, m->history) < 0) {
        tex_map_free(c);
        return NULL;
    }
    return c;
}

int tex_map_set_history(tex_map *m, const char *history)
{
    char *h = NULL;

    if (history && !(h = strdup(history)))
        return tex_error("out of memory");
    free(m->history);
    m->history = h;
    return 0;
}

void tex_map_inherit_place(tex_map *dst, const tex_map *src)
{
    if (dst->w == src->w && dst->h == src->h && src->full_w > 0) {
        dst->x0 = src->x0;
        dst->y0 = src->y0;
        dst->full_w = src->full_w;
        dst->full_h = src->full_h;
    }
}

int tex_map_inherit(tex_map *dst, const tex_map *src)
{
    tex_map_inherit_place(dst, src);
    return tex_map_set_history(dst, src->history);
}

int tex_map_add_history(tex_map *m, const char *line)
{
    size_t old = m->history ? strlen(m->history) : 0, n = strlen(line);
    char *h = realloc(m->history, old + n + 2);

    if (!h)
        return tex_error("out of memory");
    memcpy(h + old, line, n);
    h[old + n] = '\n';
    h[old + n + 1] = '\0';
    m->history = h;
    return 0;
}

void tex_stats_begin(struct tex_stats_acc *a)
{
    *a = (struct tex_stats_acc){.lo = INFINITY, .hi = -INFINITY};
}

/* A row's samples go to four lanes (x mod 4) met in a fixed order: four chains of additions
 * rather than one, and figures that depend on the map alone, not on how it was split. */
#define LANES 4
_Static_assert(sizeof(((struct tex_stats_lanes *)0)->sum) == LANES * sizeof(double),
               "stats_x86.h keeps four lanes");

/* Lane l of L takes v */
static inline void lane_take(struct tex_stats_lanes *L, int l, float v, double k0, int sums)
{
    int f = isfinite(v);
    L->lo[l] = f && v < L->lo[l] ? v : L->lo[l];
    L->hi[l] = f && v > L->hi[l] ? v : L->hi[l];
    L->n[l] += f;
    if (sums) {
        double d = f ? v - k0 : 0;
        L->sum[l] += f ? v : 0;
        L->s1[l] += d;
        L->s2[l] += d * d;
        L->nan[l] += v != v;
    }
}

static void lanes_begin(struct tex_stats_lanes *L)
{
    *L = (struct tex_stats_lanes){0};
    for (int l = 0; l < LANES; l++)
        L->lo[l] = INFINITY, L->hi[l] = -INFINITY;
}

/* Lanes x.. to the row's end of w samples, nc floats apart, then the lanes met into a */
static void lanes_end(struct tex_stats_acc *a, struct tex_stats_lanes *L, const float *px,
                      size_t x, size_t w, int nc, int sums)
{
    size_t n = 0;
    for (; x + LANES <= w; x += LANES)
#pragma GCC unroll 4
        for (int l = 0; l < LANES; l++)
            lane_take(L, l, px[(x + l) * nc], a->shift, sums);
    for (; x < w; x++)
        lane_take(L, (int)(x % LANES), px[x * nc], a->shift, sums);
    for (int l = 0; l < LANES; l++) { /* which of -0 and +0 comes first: the same either way */
        a->lo = L->lo[l] < a->lo ? L->lo[l] : a->lo;
        a->hi = L->hi[l] > a->hi ? L->hi[l] : a->hi;
        n += (size_t)L->n[l];
        a->nan += (size_t)L->nan[l];
    }
    a->n += n;
    if (sums) {
        a->sum += (L->sum[0] + L->sum[1]) + (L->sum[2] + L->sum[3]);
        a->s1 += (L->s1[0] + L->s1[1]) + (L->s1[2] + L->s1[3]);
        a->s2 += (L->s2[0] + L->s2[1]) + (L->s2[2] + L->s2[3]);
        a->nonfinite += w - n;
    }
}

/* One row of w samples, nc floats apart, into a: only the range when !sums */
static inline void row_take(struct tex_stats_acc *a, const float *px, size_t w, int nc, int sums)
{
    struct tex_stats_lanes L;
    size_t x = 0;

    lanes_begin(&L);
#ifdef TEX_X86 /* four lanes in one vector: the same doubles (t_info's and t_palette's pass) */
    if (tex_simd_level() >= TEX_SIMD_AVX2)
        x = tex_stats_row_avx2(&L, px, w, nc, a->shift, sums);
#endif
    lanes_end(a, &L, px, x, w, nc, sums);
}

/* The shift, from the first row with a finite sample: its mean */
static void take_shift(struct tex_stats_acc *a, const float *px, size_t w, int nc)
{
    double t = 0;
    size_t k = 0;
    if (a->shifted)
        return;
    for (size_t x = 0; x < w; x++)
        if (isfinite(px[x * nc]))
            t += px[x * nc], k++;
    if (k)
        a->shift = t / k, a->shifted = 1;
}

void tex_stats_add(struct tex_stats_acc *a, const float *px, size_t w, size_t rows, int nc)
{
    for (size_t y = 0; y < rows; y++, px += w * nc) {
        take_shift(a, px, w, nc);
        row_take(a, px, w, nc, 1);
    }
}

void tex_stats_add_pixels(struct tex_stats_acc *a, const float *px, size_t w, size_t rows, int nc)
{
#ifdef TEX_X86 /* three channels' lanes in three vectors, each sample where it lies */
    if (nc == 3 && tex_simd_level() >= TEX_SIMD_AVX2) {
        for (size_t y = 0; y < rows; y++, px += w * nc) {
            struct tex_stats_lanes L[3];
            double k0[3];
            for (int c = 0; c < 3; c++) {
                take_shift(&a[c], px + c, w, nc);
                lanes_begin(&L[c]);
                k0[c] = a[c].shift;
            }
            size_t x = tex_stats_pixels3_avx2(L, px, w, k0);
            for (int c = 0; c < 3; c++)
                lanes_end(&a[c], &L[c], px + c, x, w, nc, 1);
        }
        return;
    }
#endif
    for (int c = 0; c < nc; c++)
        tex_stats_add(&a[c], px + c, w, rows, nc);
}

void tex_stats_add_range(struct tex_stats_acc *a, const float *px, size_t w, size_t rows, int nc)
{
    for (size_t y = 0; y < rows; y++, px += w * nc)
        row_take(a, px, w, nc, 0);
}

void tex_stats_end(const struct tex_stats_acc *a, struct tex_stats *s)
{
    size_t n = a->n;
    double m1 = n ? a->s1 / n : 0, var = n ? a->s2 / n - m1 * m1 : 0;

    s->min = n ? a->lo : 0;
    s->max = n ? a->hi : 0;
    s->mean = n ? a->sum / n : 0;
    s->stddev = var > 0 ? sqrt(var) : 0;
    s->nonfinite = a->nonfinite;
    s->nan = a->nan;
}

void tex_map_stats(const tex_map *m, int c, struct tex_stats *s)
{
    struct tex_stats_acc a;

    tex_stats_begin(&a);
    tex_stats_add(&a, m->px + c, (size_t)m->w, (size_t)m->h, m->nc);
    tex_stats_end(&a, s);
}

int tex_parse_window(const char *text, int full_w, int full_h, int r[4])
{
    long long v[4];
    const char *s = text;
    char *end;

    for (int i = 0; i < 4; i++) {
        if (!isdigit((unsigned char)*s)) /* no sign, no space: pixels are counted from 0 */
            return -1;
        errno = 0;
        v[i] = strtoll(s, &end, 10);
        if (errno || *end != (i < 3 ? ',' : '\0'))
            return -1;
        s = end + 1;
    }
    if (v[2] < 1 || v[3] < 1 || v[0] + v[2] > full_w || v[1] + v[3] > full_h)
        return -1;
    for (int i = 0; i < 4; i++)
        r[i] = (int)v[i];
    return 0;
}

/* One row of a 2 x 2 reduction: the sums in tex_map_reduce's order (from 0, the row's two
 * pixels, then the next row's), over 4; n: the row's floats, nc: the channels. */
static void reduce_row2(const float *a, const float *b, int n, int nc, float *o)
{
    for (int x = 0, i = 0; x < n; x += nc, i += 2 * nc)
        for (int c = 0; c < nc; c++)
            o[x + c] = ((((0.0f + a[i + c]) + a[i + nc + c]) + b[i + c]) + b[i + nc + c]) / 4;
}

tex_map *tex_map_reduce(const tex_map *s)
{
    tex_map *d = tex_map_new(s->w > 1 ? s->w / 2 : 1, s->h > 1 ? s->h / 2 : 1, s->nc);
    if (!d)
        return NULL;
    int fx = s->w / d->w, fy = s->h / d->h;
    if (fx == 2 && fy == 2) { /* the common case, without the general loops */
        for (int y = 0; y < d->h; y++)
            reduce_row2(tex_map_row(s, 2 * y), tex_map_row(s, 2 * y + 1), d->w * d->nc, d->nc,
                        tex_map_row(d, y));
        return d;
    }
    for (int y = 0; y < d->h; y++) {
        for (int x = 0; x < d->w; x++) {
            float *o = tex_map_px(d, x, y);
            for (int j = 0; j < fy; j++)
                for (int i = 0; i < fx; i++) {
                    const float *p = tex_map_px(s, x * fx + i, y * fy + j);
                    for (int c = 0; c < s->nc; c++)
                        o[c] += p[c];
                }
            for (int c = 0; c < s->nc; c++)
                o[c] /= fx * fy;
        }
    }
    return d;
}
