/* test_foundation.c - maps, parameter rows, format sniffing, the EXR stream */
#define _GNU_SOURCE
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>
#ifdef __GLIBC__ /* known once a libc header is in */
#include <malloc.h>
#endif

#include "base/simd.h"
#include "textura.h"
#include "unit.h"

static void test_map_limits(void)
{
    tex_map *m;

    CHECK(tex_map_check_size(1, 1, 1) == 0, "a 1x1 map is allowed");
    CHECK(tex_map_check_size(0, 5, 1) < 0 && tex_errkind() == TEX_ERR_USAGE, "width 0 is refused");
    CHECK(tex_map_check_size(5, -1, 1) < 0, "negative height is refused");
    CHECK(tex_map_check_size(1000000000, 1, 1) < 0, "a side of 1e9 is refused");
    CHECK(strstr(tex_errmsg(), "65536") != NULL, "the message names the limit");
    CHECK(tex_map_check_size(65536, 65536, 4) < 0, "65536^2 x 4 exceeds the sample limit");
    CHECK(tex_map_check_size(32768, 32768, 1) == 0, "32768^2 x 1 is within the limit");
    CHECK(tex_map_check_size(4, 4, 5) < 0 && tex_map_check_size(4, 4, 0) < 0,
          "channels outside 1..4 are refused");
    CHECK(tex_map_check_sides(65536, 65536, 4) == 0, "65536^2 x 4 may pass in bands");
    CHECK(tex_map_check_size(65536, 65536, 1) < 0 && strstr(tex_errmsg(), "hold whole"),
          "65536^2 held whole is refused, saying so");
    CHECK(tex_map_check_sides(65537, 1, 1) < 0 && tex_map_check_sides(1, 0, 1) < 0 &&
              tex_map_check_sides(1, 1, 5) < 0 && tex_errkind() == TEX_ERR_USAGE,
          "a band's map still has sides 1..65536 and 1..4 channels");
    CHECK(tex_map_new(0, 10, 1) == NULL, "tex_map_new refuses an empty map");
    m = tex_map_new(7, 3, 3);
    CHECK(m && m->w == 7 && m->h == 3 && m->nc == 3, "tex_map_new keeps the shape");
    CHECK(m && ((uintptr_t)m->px & 63) == 0, "pixels are 64-byte aligned");
    CHECK(m && tex_map_px(m, 6, 2) == m->px + (2 * 7 + 6) * 3, "pixel addressing is row-major");
    tex_map_add_history(m, "a b");
    tex_map_add_history(m, "c");
    CHECK(m && strcmp(m->history, "a b\nc\n") == 0, "history appends one line per command");
    tex_map_free(m);
}

/* tex_pages_new: zeroed and aligned from the heap and from fresh pages alike, whole 2 MiB
 * pages counted back, and written end to end */
static void test_pages(void)
{
    const size_t sizes[] = {1, 100, 4096 * 3 + 5, (size_t)2 << 20, ((size_t)5 << 20) + 12};
    size_t none = 7;
    void *z = tex_pages_new(0, 0, &none); /* no bytes: the heap's, whatever min */
    CHECK(none == 0, "0 bytes come from the heap, given back by free");
    tex_pages_free(z, none);
    for (int k = 0; k < 5; k++)
        for (int big = 0; big < 2; big++) {
            size_t n = sizes[k], mapped = 7;
            unsigned char *p = tex_pages_new(n, big ? 1 : (size_t)1 << 40, &mapped);
            int zero = p != NULL;
            for (size_t i = 0; zero && i < n; i++)
                zero = p[i] == 0;
            uintptr_t align = big ? (uintptr_t)2 << 20 : 64; /* pages: on a huge page's bound */
            CHECKF(zero && (uintptr_t)p % align == 0, "%zu bytes (%s) come zeroed, aligned", n,
                   big ? "pages" : "heap");
            CHECKF(big ? mapped >= n && mapped % ((size_t)2 << 20) == 0 : mapped == 0,
                   "%zu bytes (%s): %zu bytes to give back", n, big ? "pages" : "heap", mapped);
            if (p)
                memset(p, 0xff, n);
            tex_pages_free(p, mapped);
        }
}

static long minor_faults(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
}

/* A band's maps made again in their sizes (16 MiB) reuse the pages of those freed: a fresh
 * mapping faults at least once per 2 MiB page on its first touch (each band's maps were a third
 * of t_palette's CPU in a pipe), a kept one not at all, and it comes zeroed all the same;
 * unset, it keeps what was written. A map over 64 MiB is not kept. */
static void test_pages_kept(void)
{
    const size_t n = (size_t)1024 * 1024 * 4;
    int zero = 1, same = 1;
    for (int round = 0; round < 3; round++) {
        tex_map *m = round < 2 ? tex_map_new(1024, 1024, 4) : tex_map_new_unset(1024, 1024, 4);
        if (!m) {
            CHECK(0, "a 16 MiB map");
            return;
        }
        for (size_t i = 0; round > 0 && i < n; i++)
            zero &= round == 1 ? m->px[i] == 0 : 1, same &= round == 2 ? m->px[i] == 1 : 1;
        long before = minor_faults();
        for (size_t i = 0; i < n; i++)
            m->px[i] = (float)round;
        long faults = minor_faults() - before;
        if (round > 0)
            CHECKF(faults < 8, "%s map of a freed one's size: %ld page faults writing its 16 MiB",
                   round == 1 ? "a" : "an unset", faults);
        tex_map_free(m);
    }
    CHECK(zero, "tex_map_new's map comes zeroed from a kept mapping");
    CHECK(same, "tex_map_new_unset's map is the kept mapping's bytes as they were left");
    tex_map *big = tex_map_new(4096, 2048, 4); /* 128 MiB: not kept */
    if (big) {
        memset(big->px, 0, (size_t)4096 * 2048 * 4 * sizeof(float));
        tex_map_free(big);
        big = tex_map_new_unset(4096, 2048, 4);
        long before = minor_faults();
        if (big)
            memset(big->px, 0, (size_t)4096 * 2048 * 4 * sizeof(float));
        CHECKF(big && minor_faults() - before >= 64, "a 128 MiB map is fresh pages each time "
               "(%ld page faults writing it)", minor_faults() - before);
        tex_map_free(big);
    }
}

/* tex_stats_add_range: the min and max tex_map_stats gives, the same bits (which of -0 and +0
 * comes first), over rows of a channel among others with NaN and infinities, added in bands */
static void test_stats_range(void)
{
    tex_map *m = tex_map_new(37, 29, 3);
    if (!m) {
        CHECK(0, "a map");
        return;
    }
    for (size_t i = 0; i < tex_map_samples(m); i++)
        m->px[i] = (float)((i * 7919) % 1000) / 100.0f - 5.0f;
    m->px[0] = -0.0f, m->px[3] = 0.0f, m->px[6] = NAN, m->px[9] = INFINITY;
    m->px[12] = -INFINITY, m->px[4] = -1e6f; /* channel 1: not channel 0's */
    int same = 1;
    for (int c = 0; c < 3; c++) {
        struct tex_stats whole, range;
        struct tex_stats_acc a;
        tex_map_stats(m, c, &whole);
        tex_stats_begin(&a);
        for (int y = 0; y < m->h; y += 5)
            tex_stats_add_range(&a, tex_map_row(m, y) + c, (size_t)m->w,
                                (size_t)(m->h - y < 5 ? m->h - y : 5), m->nc);
        tex_stats_end(&a, &range);
        same &= !memcmp(&whole.min, &range.min, sizeof whole.min) &&
                !memcmp(&whole.max, &range.max, sizeof whole.max);
    }
    CHECK(same, "tex_stats_add_range: tex_map_stats' min and max, bit for bit, in bands");
    tex_map_free(m);
}

/* The statistics at every SIMD level the CPU has are the scalar path's, bit for bit: rows of
 * every width from 1 to 41 (a vector's lanes and the tail), 1 to 4 channels, with -0, +0,
 * NaN and infinities, the sums and the range alone */
static void test_stats_simd(void)
{
    int same = 1, cases = 0;
    for (int nc = 1; nc <= 4; nc++)
        for (int w = 1; w <= 41; w += 4 - nc % 3) {
            tex_map *m = tex_map_new(w, 7, nc);
            if (!m) {
                CHECK(0, "a map");
                return;
            }
            for (size_t i = 0; i < tex_map_samples(m); i++)
                m->px[i] = (float)((i * 7919 + (size_t)w) % 1013) / 97.0f - 5.0f;
            const float odd[] = {-0.0f, 0.0f, NAN, INFINITY, -INFINITY, 1e30f, -1e-30f};
            for (size_t i = 0; i < tex_map_samples(m); i += 5)
                m->px[i] = odd[i / 5 % 7];
            if (w % 2) /* zeros at the range's ends, -0 and +0 in one lane: which one stays */
                for (size_t i = 0; i < tex_map_samples(m); i++)
                    m->px[i] = i % 4 == 0 ? (i / 4 % 2 ? 0.0f : -0.0f)
                                          : (float)(w % 4 == 1 ? i % 3 + 1 : -(int)(i % 3) - 1);
            for (int c = 0; c < nc; c++)
                for (int sums = 0; sums < 2; sums++) {
                    struct tex_stats s[2];
                    for (int lv = 0; lv < 2; lv++) {
                        struct tex_stats_acc a;
                        tex_simd_limit(lv ? TEX_SIMD_AVX512 : TEX_SIMD_SCALAR);
                        tex_stats_begin(&a);
                        for (int y = 0; y < m->h; y += 3)
                            (sums ? tex_stats_add : tex_stats_add_range)(
                                &a, tex_map_row(m, y) + c, (size_t)m->w,
                                (size_t)(m->h - y < 3 ? m->h - y : 3), m->nc);
                        tex_stats_end(&a, &s[lv]);
                    }
                    same &= !memcmp(&s[0], &s[1], sizeof s[0]);
                    cases++;
                }
            /* every channel at once (tex_stats_add_pixels), at each level: the scalar path's
             * channel by channel */
            for (int lv = 0; lv < 2; lv++) {
                struct tex_stats_acc a[4], one;
                struct tex_stats all, each;
                tex_simd_limit(lv ? TEX_SIMD_AVX512 : TEX_SIMD_SCALAR);
                for (int c = 0; c < nc; c++)
                    tex_stats_begin(&a[c]);
                for (int y = 0; y < m->h; y += 3)
                    tex_stats_add_pixels(a, tex_map_row(m, y), (size_t)m->w,
                                         (size_t)(m->h - y < 3 ? m->h - y : 3), m->nc);
                tex_simd_limit(TEX_SIMD_SCALAR);
                for (int c = 0; c < nc; c++) {
                    tex_stats_begin(&one);
                    tex_stats_add(&one, tex_map_row(m, 0) + c, (size_t)m->w, (size_t)m->h, m->nc);
                    tex_stats_end(&one, &each);
                    tex_stats_end(&a[c], &all);
                    same &= !memcmp(&all, &each, sizeof all);
                    cases++;
                }
            }
            tex_map_free(m);
        }
    tex_simd_limit(TEX_SIMD_AVX512);
    CHECKF(same, "statistics at the CPU's SIMD level (%s) are the scalar path's bits (%d cases)",
           tex_simd_name(tex_simd_level()), cases);
}

/* tex_read_fd: a large file into pages, a small one and a pipe into the heap; a buffer of
 * pages grows onto the heap with its bytes */
static void test_read_fd(void)
{
    char path[] = "/tmp/test_foundation.XXXXXX";
    int fd = mkstemp(path);
    size_t n = ((size_t)3 << 20) + 5;
    unsigned char *src = malloc(n);
    for (size_t i = 0; src && i < n; i++)
        src[i] = (unsigned char)(i * 2654435761u >> 24);
    CHECK(fd >= 0 && src && write(fd, src, n) == (ssize_t)n, "a 3 MiB file written");
    for (int big = 1; big >= 0 && fd >= 0 && src; big--) { /* the file cut short after */
        size_t len = big ? n : 1000;
        tex_buf b = {0};
        if (ftruncate(fd, (off_t)len) < 0 || lseek(fd, 0, SEEK_SET) != 0)
            break;
        int r = tex_read_fd(fd, &b, "test");
        CHECKF(r == 0 && b.len == len && memcmp(b.data, src, len) == 0 &&
                   (big ? b.mapped >= len : b.mapped == 0),
               "tex_read_fd: %zu bytes read whole, into %s", len, big ? "pages" : "the heap");
        if (big) {
            r = tex_buf_reserve(&b, 2 * b.cap);
            CHECK(r == 0 && b.mapped == 0 && b.cap >= 2 * len && memcmp(b.data, src, len) == 0,
                  "a buffer of pages grows onto the heap, its bytes kept");
        }
        tex_buf_free(&b);
        CHECK(!b.data && !b.len && !b.cap && !b.mapped, "tex_buf_free empties the buffer");
    }
    if (fd >= 0)
        close(fd);
    unlink(path);
    free(src);
}

struct p {
    int n;
    double x;
    int e;
    struct tex_reals l;
    float col[4];
};

static const struct tex_param rows[] = {
    TEX_INT(struct p, n, 'n', 4, 1, 30, "N", "count"),
    TEX_REAL(struct p, x, 0, 0.5, 0, 1, "X", "fraction"),
    TEX_ENUM(struct p, e, 0, "b", "a|b|c", "choice"),
    TEX_REALS(struct p, l, 0, "1,2", -10, 10, 4, "LIST", "list"),
    TEX_COLOR(struct p, col, 0, "#ff8000", "colour"),
    {0}};

static void test_params(void)
{
    struct p v;

    CHECK(tex_params_defaults(rows, &v) == 0, "defaults apply");
    CHECK(v.n == 4 && v.x == 0.5 && v.e == 1 && v.l.n == 2 && v.l.v[1] == 2,
          "defaults have the declared values");
    CHECK(fabsf(v.col[0] - 1) < 1e-6 && fabsf(v.col[1] - 128 / 255.0f) < 1e-6 && v.col[3] == 1,
          "hex colour default parses");
    CHECK(tex_param_set(&rows[0], &v, "31") < 0 && tex_errkind() == TEX_ERR_USAGE,
          "an int above the range is a usage error");
    CHECK(strstr(tex_errmsg(), "--n must be 1..30") != NULL, "the message gives the range");
    CHECK(tex_param_set(&rows[0], &v, "2.5") < 0, "a fraction is not an int");
    CHECK(tex_param_set(&rows[0], &v, "12abc") < 0, "trailing garbage is refused");
    CHECK(tex_param_set(&rows[1], &v, "nan") < 0 && tex_param_set(&rows[1], &v, "inf") < 0,
          "NaN and infinity are refused");
    CHECK(tex_param_set(&rows[2], &v, "c") == 0 && v.e == 2, "enum by name");
    CHECK(tex_param_set(&rows[2], &v, "d") < 0, "unknown enum name is refused");
    CHECK(tex_param_set(&rows[3], &v, "1,,2") < 0, "an empty list item is refused");
    CHECK(tex_param_set(&rows[3], &v, "1,2,3,4,5") < 0, "too many list items are refused");
    CHECK(tex_param_set(&rows[3], &v, "-3,4.5") == 0 && v.l.n == 2 && v.l.v[0] == -3,
          "a list parses");
    CHECK(tex_param_set(&rows[4], &v, "0.1,0.2,0.3") == 0 && fabsf(v.col[2] - 0.3f) < 1e-6,
          "r,g,b colour parses");
    CHECK(tex_param_set(&rows[4], &v, "#12345") < 0 && tex_param_set(&rows[4], &v, "1,2,3") < 0,
          "malformed colours are refused");
}

static void test_sniff(void)
{
    static const struct {
        const char *bytes;
        size_t n;
        enum tex_format f;
    } cases[] = {
        {"\x76\x2f\x31\x01\x02\0\0\0", 8, TEX_FMT_EXR},
        {"\x89PNG\r\n\x1a\n", 8, TEX_FMT_PNG},
        {"II*\0\x08\0\0\0", 8, TEX_FMT_TIFF},
        {"MM\0*\0\0\0\x08", 8, TEX_FMT_TIFF},
        {"P5\n64 64\n255\n", 13, TEX_FMT_PNM},
        {"Pf\n64 64\n-1\n", 12, TEX_FMT_PFM},
        {"\xff\xd8\xff\xe0", 4, TEX_FMT_JPEG},
        {"#?RADIANCE\n", 11, TEX_FMT_HDR},
        {"GIF89a\x01\0", 8, TEX_FMT_GIF},
        {"hello, world", 12, TEX_FMT_UNKNOWN},
        {"P9\n", 3, TEX_FMT_UNKNOWN},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        CHECKF(tex_format_sniff(cases[i].bytes, cases[i].n) == cases[i].f, "sniff case %zu (%s)",
               i, tex_format_name(cases[i].f));
    CHECK(tex_format_from_name("a/b.TIFF") == TEX_FMT_TIFF && tex_format_from_name("x.pgm") ==
              TEX_FMT_PGM && tex_format_from_name("x.pnm") == TEX_FMT_PNM &&
              tex_format_from_name("dir.png/x") == TEX_FMT_UNKNOWN,
          "formats from extensions");
}

static void test_stream(void)
{
    tex_map *m = tex_map_new(37, 11, 4), *r;
    tex_buf b = {0};
    int same = 1, fails = 0;

    for (size_t i = 0; i < tex_map_samples(m); i++)
        m->px[i] = (float)((int)(i * 2654435761u % 1000) - 500) / 7.0f;
    m->px[5] = NAN;
    m->px[6] = -INFINITY;
    m->px[7] = 1e-40f; /* a denormal survives float32 exactly */
    m->subregions = 3;
    tex_map_add_history(m, "t_test 'quoted arg'");
    CHECK(tex_exr_encode(m, TEX_COMPRESS_NONE, &b) == 0, "encode a 37x11x4 map");
    r = tex_exr_decode(b.data, b.len, "test");
    CHECK(r && r->w == 37 && r->h == 11 && r->nc == 4, "decode keeps the shape");
    for (size_t i = 0; r && i < tex_map_samples(m); i++)
        same &= memcmp(&m->px[i], &r->px[i], 4) == 0;
    CHECK(r && same, "the round trip is bit-exact (NaN, infinity and denormals included)");
    CHECK(r && r->subregions == 3, "textura:subregions survives");
    CHECK(r && r->history && strcmp(r->history, m->history) == 0, "textura:history survives");
    tex_map_free(r);

    /* Every truncation must fail cleanly: never crash, never decode. */
    for (size_t cut = 0; cut < b.len; cut += 1 + cut / 8) {
        tex_map *t = tex_exr_decode(b.data, cut, "cut");
        fails += t != NULL;
        tex_map_free(t);
    }
    CHECK(fails == 0, "no truncated stream decodes");

    /* A header that claims a huge data window is refused before allocation. */
    {
        unsigned char *p = memmem(b.data, b.len, "dataWindow\0box2i", 16);
        if (p) {
            int32_t big = 1 << 30;
            memcpy(p + 16 + 4 + 8, &big, 4); /* max.x */
            r = tex_exr_decode(b.data, b.len, "huge");
            CHECK(r == NULL, "a data window of 2^30 pixels is refused");
            tex_map_free(r);
        } else
            CHECK(0, "found the data window in the header");
    }
    tex_buf_free(&b);

    for (int nc = 1; nc <= 4; nc++) {
        tex_map *s = tex_map_new(5, 4, nc);
        int eq = 1;
        for (size_t i = 0; i < tex_map_samples(s); i++)
            s->px[i] = (float)i;
        for (int c = TEX_COMPRESS_NONE; c <= TEX_COMPRESS_PIZ; c++) {
            tex_buf e = {0};
            tex_map *d = NULL;
            if (tex_exr_encode(s, c, &e) == 0)
                d = tex_exr_decode(e.data, e.len, "x");
            eq &= d && d->nc == nc && memcmp(d->px, s->px, tex_map_samples(s) * 4) == 0;
            tex_map_free(d);
            tex_buf_free(&e);
        }
        CHECKF(eq, "%d-channel maps round-trip through none, zip and piz", nc);
        tex_map_free(s);
    }
    tex_map_free(m);
}

static void test_noise(void)
{
    tex_noise_table *t = tex_noise_new(42, 256, 0);
    double maxd = 0, lattice = 0;

    CHECK(t != NULL, "a noise table from the public header");
    if (!t)
        return;
    for (int i = -3; i <= 3; i++)
        lattice = fmax(lattice, fabs(tex_noise3(t, i, 2 * i, -i)));
    CHECK(lattice == 0, "noise vanishes at lattice points");
    for (int i = 0; i < 10000; i++) {
        double x = i * 0.0137;
        double d = fabs(tex_noise3(t, x + 1e-4, 0.3, 0.7) - tex_noise3(t, x, 0.3, 0.7));
        maxd = fmax(maxd, d);
    }
    CHECKF(maxd < 1e-3, "noise is continuous (max step %g over 1e-4)", maxd);
    CHECK(isfinite(tex_noise3(t, 1e9 + 0.5, -1e9 + 0.25, 3e8)), "huge coordinates stay finite");
    CHECK(tex_noise_new(42, 1, 0) == NULL && strstr(tex_errmsg(), "gradients"),
          "a table of one gradient is refused, the message naming the gradients");
    tex_noise_delete(t);
}

/* Progress from many threads: each report larger than the last, 100 at the end. */
static int reports, last_percent = -1, backwards;
static void on_progress(long done, long total, void *arg)
{
    (void)arg;
    backwards |= done <= last_percent || total != 100;
    last_percent = (int)done;
    reports++;
}

static void test_progress(void)
{
    tex_set_progress_handler(on_progress, NULL);
    tex_progress_stage(0.5, 1000);
#pragma omp parallel for
    for (int i = 0; i < 1000; i++)
        tex_progress_add(1);
    CHECK(last_percent == 50, "a stage of half the bar ends at 50%");
    tex_progress_stage(1, 10);
    tex_progress_hold(1);
    tex_progress_stage(1, 5); /* held: an inner part's stages do not count */
    tex_progress_add(5);
    tex_progress_hold(0);
    CHECK(last_percent == 50, "nothing is reported while held");
#pragma omp parallel for
    for (int i = 0; i < 10; i++)
        tex_progress_add(1);
    tex_progress_done();
    CHECK(last_percent == 100 && !backwards, "progress only grows, and ends at 100%");
    CHECK(reports <= 101, "at most one report per percent");
    tex_set_progress_handler(NULL, NULL);
    reports = 0;
    tex_progress_stage(1, 10);
    tex_progress_add(10);
    tex_progress_done();
    CHECK(reports == 0, "no handler, no reports");
}

/* tex_keep_heap: a block glibc would map on its own whatever it has seen freed (40 MiB, over
 * the 32 MiB that its dynamic threshold stops at) comes from the heap, so that freeing it keeps
 * its pages for the next.  glibc's own allocator only: a sanitizer's replaces it. */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SANITIZED 1
#endif
#endif
static void test_keep_heap(void)
{
#if defined(__GLIBC__) && !defined(SANITIZED)
    size_t before = mallinfo2().hblks, during;
    tex_keep_heap();
    char *p = malloc(40 << 20); /* untouched: no page faulted in */
    during = mallinfo2().hblks;
    free(p);
    CHECKF(p && during == before, "tex_keep_heap: 40 MiB from the heap, not a mapping of its "
                                  "own (%zu mapped blocks, %zu before)", during, before);
#else
    printf("# tex_keep_heap: glibc's allocator is not the one in use\n");
#endif
}

int main(void)
{
    test_progress();
    test_map_limits();
    test_pages();
    test_pages_kept();
    test_stats_range();
    test_stats_simd();
    test_keep_heap();
    test_read_fd();
    test_params();
    test_sniff();
    test_stream();
    test_noise();
    return unit_done();
}
