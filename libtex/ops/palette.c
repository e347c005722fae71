/* palette.c - palette files, gradient lookup in RGB or OKLab, indexed colours */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/error.h"
#include "base/map.h"
#include "base/paths.h"
#include "base/simd.h"
#include "io/file.h"
#include "base/nearest.h"
#include "ops/palette.h"
#include "ops/palette_srgb.h"
#include "ops/x86/palette_x86.h"


#define MAX_FILE (4 << 20)   /* a palette is text: refuse anything larger */
#define MAX_ENTRIES 65536    /* stops, and index entries */
#define MAX_ID (1 << 24)

/* ---- colour spaces (Ottosson's OKLab, sRGB transfer) ---- */

static double srgb_decode(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* c^(1/2.4) = c^(5/12) for c in (0.0031308, 1) to a relative 1e-14: c = m 2^e with m in
 * [0.5, 1) and e in -8..0; 2^(5e/12) from a table, m^(5/12) from its Taylor polynomial of
 * degree 6 about the centre of m's 32nd of [0.5, 1), where |t| <= 1/128 leaves a remainder
 * below 1e-14, summed by Estrin's scheme (a short chain of dependent operations): cheaper
 * than libm's pow, three times per lookup. */
static struct tex_srgb_enc enc;
static pthread_once_t enc_once = PTHREAD_ONCE_INIT;

static void enc_setup(void)
{
    const double a = 5.0 / 12;
    for (int i = 0; i < ENC_PIECES; i++) {
        double c0 = 0.5 + (i + 0.5) / (2 * ENC_PIECES), coef = pow(c0, a);
        for (int k = 0; k <= ENC_DEGREE; k++) { /* binomial(a, k) c0^(a - k) */
            enc.coef[k][i] = coef;
            coef *= (a - k) / ((k + 1) * c0);
        }
    }
    for (int e = 0; e < 9; e++)
        enc.scale[e] = pow(2, -5.0 * e / 12);
}

static double enc_pow(double c)
{
    uint64_t bits; /* c = m 2^e, as frexp has them: c is positive and normal */
    memcpy(&bits, &c, sizeof bits);
    int e = (int)(bits >> 52) - 1022;
    bits = (bits & ((UINT64_C(1) << 52) - 1)) | UINT64_C(1022) << 52;
    double m;
    memcpy(&m, &bits, sizeof m);
    int i = (int)((m - 0.5) * (2 * ENC_PIECES));
    double p[ENC_DEGREE + 1];
    for (int k = 0; k <= ENC_DEGREE; k++)
        p[k] = enc.coef[k][i];
    double t = m - (0.5 + (i + 0.5) / (2 * ENC_PIECES)), t2 = t * t;
    double y = (p[0] + p[1] * t) + t2 * (p[2] + p[3] * t) + t2 * t2 * (p[4] + p[5] * t + t2 * p[6]);
    return y * enc.scale[-e];
}

/* The sRGB encoding of linear c as a float: (float)(1.055 pow(c, 1/2.4) - 0.055) above the
 * linear toe.  enc_pow's value lies within a relative 1e-14 of pow's, so where every double
 * within 2e-12 of its result rounds to the same float, that float is pow's, to the bit;
 * else (about one value in 10^4) pow decides. */
static float srgb_encode(double c)
{
    if (c <= 0.0)
        return 0.0f;
    if (c >= 1.0)
        return 1.0f;
    if (c <= 0.0031308)
        return (float)(12.92 * c);
    if (c == c) { /* not a NaN */
        double v = 1.055 * enc_pow(c) - 0.055;
        float lo = (float)(v - 2e-12), hi = (float)(v + 2e-12);
        if (lo == hi)
            return lo;
    }
    return (float)(1.055 * pow(c, 1 / 2.4) - 0.055);
}

float tex_palette_srgb_encode(double c)
{
    return srgb_encode(c);
}

void tex_srgb_to_oklab(const float rgb[3], float lab[3])
{
    double r = srgb_decode(rgb[0]), g = srgb_decode(rgb[1]), b = srgb_decode(rgb[2]);
    double l = cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b);
    double m = cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b);
    double s = cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b);
    lab[0] = (float)(0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s);
    lab[1] = (float)(1.9779984951 * l - 2.4285922050 * m + 0.4505937099 * s);
    lab[2] = (float)(0.0259040371 * l + 0.7827717662 * m - 0.8086757660 * s);
}

/* OKLab to linear sRGB, before the encoding */
static void oklab_linear(const float lab[3], double lin[3])
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        c[k] = lab[0] + ok_lms[k][0] * lab[1] + ok_lms[k][1] * lab[2];
        c[k] = c[k] * c[k] * c[k];
    }
    for (int k = 0; k < 3; k++)
        lin[k] = ok_rgb[k][0] * c[0] + ok_rgb[k][1] * c[1] + ok_rgb[k][2] * c[2];
}

/* tex_oklab_to_srgb of n colours, their channels in separate arrays: eight at a time where
 * the CPU has AVX-512, four with AVX2, the same floats */
static void oklab_srgb_n(const float *const lab[3], float *const rgb[3], int n)
{
    int i = 0;
    pthread_once(&enc_once, enc_setup);
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX512)
        i = tex_oklab_srgb_avx512(&enc, lab, rgb, n);
    else if (tex_simd_level() >= TEX_SIMD_AVX2)
        i = tex_oklab_srgb_avx2(&enc, lab, rgb, n);
#endif
    for (; i < n; i++) {
        double lin[3];
        oklab_linear((const float[3]){lab[0][i], lab[1][i], lab[2][i]}, lin);
        for (int c = 0; c < 3; c++)
            rgb[c][i] = srgb_encode(lin[c]);
    }
}

void tex_oklab_to_srgb(const float lab[3], float rgb[3])
{
    double lin[3];
    oklab_linear(lab, lin);
    pthread_once(&enc_once, enc_setup);
    for (int k = 0; k < 3; k++)
        rgb[k] = srgb_encode(lin[k]);
}

/* ---- construction ---- */

tex_palette *tex_palette_new(enum tex_palette_space space)
{
    tex_palette *p = calloc(1, sizeof *p);
    if (!p)
        tex_error("out of memory");
    else
        p->space = space;
    return p;
}

void tex_palette_free(tex_palette *p)
{
    if (!p)
        return;
    free(p->name);
    free(p->stops);
    free(p->index);
    free(p);
}

static int grow(void **a, int n, size_t size)
{
    /* capacity doubles at powers of two */
    if (n && (n & (n - 1)))
        return 0;
    void *b = realloc(*a, (size_t)(n ? 2 * n : 4) * size);
    if (!b)
        return tex_error("out of memory");
    *a = b;
    return 0;
}

int tex_palette_add_stop(tex_palette *p, float pos, const float rgba[4])
{
    struct tex_palette_stop *s;

    if (p->nstops >= MAX_ENTRIES)
        return tex_error("more than %d colour stops", MAX_ENTRIES);
    if (grow((void **)&p->stops, p->nstops, sizeof *p->stops) < 0)
        return -1;
    s = &p->stops[p->nstops++];
    s->pos = pos;
    memcpy(s->rgba, rgba, sizeof s->rgba);
    tex_srgb_to_oklab(rgba, s->lab);
    s->lab[3] = rgba[3];
    return 0;
}

/* ---- parsing ---- */

struct parser {
    const char *name;
    int line;
};

static int perr(const struct parser *ps, const char *fmt, const char *arg)
{
    char msg[160];
    snprintf(msg, sizeof msg, fmt, arg);
    return tex_error("%s:%d: %s", ps->name, ps->line, msg);
}

static int hexval(int c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    c = tolower(c);
    return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

/* #rgb, #rrggbb or #rrggbbaa */
static int parse_hex(const char *tok, float rgba[4])
{
    size_t n = strlen(tok) - 1;
    int d[8];

    if (n != 3 && n != 6 && n != 8)
        return -1;
    for (size_t i = 0; i < n; i++)
        if ((d[i] = hexval((unsigned char)tok[1 + i])) < 0)
            return -1;
    rgba[3] = 1.0f;
    for (int c = 0; c < (n == 8 ? 4 : 3); c++)
        rgba[c] = n == 3 ? (float)(d[c] * 17) / 255.0f : (float)(d[2 * c] * 16 + d[2 * c + 1]) / 255.0f;
    return 0;
}

static int parse_unit(const struct parser *ps, const char *tok, const char *what, float *out)
{
    char *end;
    double v;

    errno = 0;
    v = strtod(tok, &end);
    if (end == tok || *end || errno || !isfinite(v)) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s: not a number: '%%s'", what);
        return perr(ps, msg, tok);
    }
    if (v < 0 || v > 1) {
        char msg[96];
        snprintf(msg, sizeof msg, "%s must be in 0..1 (got %%s)", what);
        return perr(ps, msg, tok);
    }
    *out = (float)v;
    return 0;
}

/* A colour from tokens: one hex token, or 3 or 4 numbers in [0,1]. */
static int parse_colour(const struct parser *ps, char **tok, int ntok, float rgba[4])
{
    static const char *const comp[4] = {"red", "green", "blue", "alpha"};

    if (ntok == 0)
        return perr(ps, "missing colour%s", "");
    if (tok[0][0] == '#') {
        if (ntok > 1)
            return perr(ps, "unexpected '%s' after the colour", tok[1]);
        if (parse_hex(tok[0], rgba) < 0)
            return perr(ps, "bad hex colour '%s' (want #rrggbb or #rrggbbaa)", tok[0]);
        return 0;
    }
    if (ntok < 3)
        return perr(ps, "a colour needs r g b [a] or #rrggbb%s", "");
    if (ntok > 4)
        return perr(ps, "unexpected '%s' after the colour", tok[4]);
    rgba[3] = 1.0f;
    for (int c = 0; c < ntok; c++)
        if (parse_unit(ps, tok[c], comp[c], &rgba[c]) < 0)
            return -1;
    return 0;
}

static int cmp_entry(const void *a, const void *b)
{
    const struct tex_palette_entry *x = a, *y = b;
    return (x->id > y->id) - (x->id < y->id);
}

static int parse_line(tex_palette *p, struct parser *ps, char *s)
{
    char *tok[16];
    int n = 0;
    float rgba[4];

    /* Tokens split at blanks; a '#' token followed by a blank (or alone)
     * starts a trailing comment, as does '#' at the start of the line. */
    for (char *t = strtok(s, " \t\r\v\f"); t; t = strtok(NULL, " \t\r\v\f")) {
        if (t[0] == '#' && (n == 0 || t[1] == '\0'))
            break;
        if (n == 16)
            return perr(ps, "too many fields%s", "");
        tok[n++] = t;
    }
    if (n == 0)
        return 0;
    if (!strcmp(tok[0], "space")) {
        if (n != 2 || (strcmp(tok[1], "rgb") && strcmp(tok[1], "oklab")))
            return perr(ps, "want 'space rgb' or 'space oklab'%s", "");
        p->space = !strcmp(tok[1], "rgb") ? TEX_SPACE_RGB : TEX_SPACE_OKLAB;
        return 0;
    }
    if (!strcmp(tok[0], "index")) {
        char *end;
        long id;
        if (n < 3)
            return perr(ps, "want 'index ID COLOUR'%s", "");
        errno = 0;
        id = strtol(tok[1], &end, 10);
        if (end == tok[1] || *end || errno || id < 0 || id > MAX_ID) {
            char msg[64];
            snprintf(msg, sizeof msg, "index: region id must be 0..%d (got '%%s')", MAX_ID);
            return perr(ps, msg, tok[1]);
        }
        if (parse_colour(ps, tok + 2, n - 2, rgba) < 0)
            return -1;
        for (int i = 0; i < p->nindex; i++)
            if (p->index[i].id == id)
                return perr(ps, "index %s given twice", tok[1]);
        if (p->nindex >= MAX_ENTRIES)
            return perr(ps, "too many index entries%s", "");
        if (grow((void **)&p->index, p->nindex, sizeof *p->index) < 0)
            return -1;
        p->index[p->nindex].id = (int)id;
        memcpy(p->index[p->nindex++].rgba, rgba, sizeof rgba);
        return 0;
    }
    if (!(isdigit((unsigned char)tok[0][0]) || tok[0][0] == '.' || tok[0][0] == '-' ||
          tok[0][0] == '+'))
        return perr(ps, "unknown keyword '%s' (want a stop position, 'space' or 'index')", tok[0]);
    {
        float pos;
        if (parse_unit(ps, tok[0], "stop position", &pos) < 0 ||
            parse_colour(ps, tok + 1, n - 1, rgba) < 0)
            return -1;
        if (p->nstops && pos < p->stops[p->nstops - 1].pos) {
            char msg[96];
            snprintf(msg, sizeof msg, "stops out of order: %%s after %.9g", p->stops[p->nstops - 1].pos);
            return perr(ps, msg, tok[0]);
        }
        if (tex_palette_add_stop(p, pos, rgba) < 0)
            return perr(ps, "%s", tex_errmsg());
    }
    return 0;
}

tex_palette *tex_palette_parse(const char *text, size_t len, const char *name)
{
    struct parser ps = {name, 0};
    tex_palette *p = tex_palette_new(TEX_SPACE_RGB);
    size_t i = 0;

    if (!p)
        return NULL;
    while (i < len) {
        size_t e = i;
        char buf[1024];
        while (e < len && text[e] != '\n')
            e++;
        ps.line++;
        if (e - i >= sizeof buf) {
            perr(&ps, "line too long%s", "");
            goto fail;
        }
        memcpy(buf, text + i, e - i);
        buf[e - i] = '\0';
        if (memchr(buf, '\0', e - i)) {
            perr(&ps, "not a text file%s", "");
            goto fail;
        }
        if (parse_line(p, &ps, buf) < 0)
            goto fail;
        i = e + 1;
    }
    if (p->nstops == 0 && p->nindex == 0) {
        tex_error("%s:%d: empty palette: no colour stops or index entries", name,
                  ps.line ? ps.line : 1);
        goto fail;
    }
    if (p->nindex > 1)
        qsort(p->index, (size_t)p->nindex, sizeof *p->index, cmp_entry);
    /* Only indexed colours: they double as evenly spaced gradient stops. */
    if (p->nstops == 0)
        for (int k = 0; k < p->nindex; k++)
            if (tex_palette_add_stop(p, p->nindex > 1 ? (float)k / (float)(p->nindex - 1) : 0.0f,
                                     p->index[k].rgba) < 0)
                goto fail;
    if (!(p->name = strdup(name))) {
        tex_error("out of memory");
        goto fail;
    }
    return p;
fail:
    tex_palette_free(p);
    return NULL;
}

/* ---- finding and loading ---- */

static int is_file_name(const char *s)
{
    size_t n = strlen(s);
    return strchr(s, '/') || (n >= 4 && !strcmp(s + n - 4, ".pal"));
}

static int try_dir(const char *dir, size_t dlen, const char *name, char *buf, size_t n)
{
    if (dlen == 0)
        return 0;
    if ((size_t)snprintf(buf, n, "%.*s/%s.pal", (int)dlen, dir, name) >= n)
        return 0;
    return access(buf, R_OK) == 0;
}

/* The folders palettes are looked up in, in order (palette.h): fn(dir, dlen, ctx) for each
 * until it returns 1; returns 1 if one did. */
static int each_dir(int (*fn)(const char *dir, size_t dlen, void *ctx), void *ctx)
{
    const char *env = getenv("TEXTURA_PALETTES");

    while (env && *env) {
        const char *e = strchr(env, ':');
        size_t dl = e ? (size_t)(e - env) : strlen(env);
        if (fn(env, dl, ctx))
            return 1;
        env = e ? e + 1 : NULL;
    }
    {
        char dir[PATH_MAX + 16];
        snprintf(dir, sizeof dir, "%s/palettes", tex_install_dir(TEX_DIR_DATA));
        return fn(dir, strlen(dir), ctx);
    }
}

struct find_ctx {
    const char *name;
    char *buf;
    size_t n;
};

static int find_in(const char *dir, size_t dlen, void *ctx)
{
    struct find_ctx *c = ctx;
    return try_dir(dir, dlen, c->name, c->buf, c->n);
}

/* The names of the palettes in the search path, sorted and without repeats, in buf. */
struct names_ctx {
    char names[256][64];
    int n;
};

static int list_in(const char *dir, size_t dlen, void *ctx)
{
    struct names_ctx *c = ctx;
    char path[PATH_MAX];
    DIR *d;
    struct dirent *e;
    if (dlen == 0 || (size_t)snprintf(path, sizeof path, "%.*s", (int)dlen, dir) >= sizeof path ||
        !(d = opendir(path)))
        return 0;
    while ((e = readdir(d)) && c->n < 256) {
        size_t l = strlen(e->d_name);
        int dup = 0;
        if (l <= 4 || l - 4 >= sizeof c->names[0] || strcmp(e->d_name + l - 4, ".pal"))
            continue;
        for (int i = 0; i < c->n && !dup; i++)
            dup = !strncmp(c->names[i], e->d_name, l - 4) && !c->names[i][l - 4];
        if (!dup)
            snprintf(c->names[c->n++], sizeof c->names[0], "%.*s", (int)(l - 4), e->d_name);
    }
    closedir(d);
    return 0;
}

static int cmp_name(const void *a, const void *b)
{
    return strcmp(a, b);
}

int tex_palette_names(char *buf, size_t n)
{
    struct names_ctx *c = calloc(1, sizeof *c);
    size_t used = 0;
    if (n)
        buf[0] = '\0';
    if (!c)
        return 0;
    each_dir(list_in, c);
    qsort(c->names, (size_t)c->n, sizeof c->names[0], cmp_name);
    for (int i = 0; i < c->n && used < n; i++)
        used += (size_t)snprintf(buf + used, n - used, "%s%s", i ? ", " : "", c->names[i]);
    int k = c->n;
    free(c);
    return k;
}

int tex_palette_find(const char *name, char *buf, size_t n)
{
    struct find_ctx c = {name, buf, n};
    char known[1024];

    if (!*name)
        return tex_usage_error("empty palette name");
    if (is_file_name(name)) {
        if ((size_t)snprintf(buf, n, "%s", name) >= n)
            return tex_usage_error("palette file name too long");
        return 0;
    }
    for (const char *ch = name; *ch; ch++)
        if (!isalnum((unsigned char)*ch) && !strchr("._+-", *ch))
            return tex_usage_error("bad palette name '%s' (letters, digits, '.', '_', '+', '-')",
                                   name);
    if (each_dir(find_in, &c))
        return 0;
    if (tex_palette_names(known, sizeof known) > 0) {
        struct tex_nearest nr;
        char near[96] = "";
        tex_nearest_init(&nr, name);
        for (const char *k = known; *k;) { /* "brick, clouds, ..." */
            size_t len = strcspn(k, ",");
            tex_nearest_try(&nr, k, len);
            k += len;
            k += strspn(k, ", ");
        }
        if (tex_nearest_name(&nr))
            snprintf(near, sizeof near, "did you mean %s? ", tex_nearest_name(&nr));
        return tex_usage_error("unknown palette '%s' (%sknown: %s; or a palette file)", name,
                               near, known);
    }
    return tex_usage_error("unknown palette '%s' (no %s.pal in $TEXTURA_PALETTES or %s/palettes)",
                           name, name, tex_install_dir(TEX_DIR_DATA));
}

/* A name that is no palette's but an existing file's, as netpbm's tools take a file: its
 * path in buf.  tex_palette_find takes no such file, so the editor's names reach none of
 * the server's files. */
static int plain_file(const char *name, char *buf, size_t n)
{
    struct find_ctx c = {name, buf, n};
    struct stat st;
    /* the folders are searched only for a name a file has: tex_palette_find searches them */
    return !is_file_name(name) && stat(name, &st) == 0 && S_ISREG(st.st_mode) &&
           !each_dir(find_in, &c) && (size_t)snprintf(buf, n, "%s", name) < n;
}

tex_palette *tex_palette_load(const char *name_or_file)
{
    char path[PATH_MAX];
    char *text;
    size_t len;
    tex_palette *p;

    if (!plain_file(name_or_file, path, sizeof path) &&
        tex_palette_find(name_or_file, path, sizeof path) < 0)
        return NULL;
    if (!(text = tex_read_text(path, MAX_FILE, &len, "a palette")))
        return NULL;
    p = tex_palette_parse(text, len, path);
    free(text);
    return p;
}

/* ---- writing ---- */

static void put_colour(FILE *fp, const float c[4])
{
    fprintf(fp, " %.9g %.9g %.9g", c[0], c[1], c[2]);
    if (c[3] != 1.0f)
        fprintf(fp, " %.9g", c[3]);
}

int tex_palette_write(const tex_palette *p, FILE *fp)
{
    fprintf(fp, "# Textura palette (textura-palette(5))\nspace %s\n",
            p->space == TEX_SPACE_OKLAB ? "oklab" : "rgb");
    for (int i = 0; i < p->nstops; i++) {
        fprintf(fp, "%.9g", p->stops[i].pos);
        put_colour(fp, p->stops[i].rgba);
        fputc('\n', fp);
    }
    for (int i = 0; i < p->nindex; i++) {
        fprintf(fp, "index %d", p->index[i].id);
        put_colour(fp, p->index[i].rgba);
        fputc('\n', fp);
    }
    if (fflush(fp) != 0 || ferror(fp))
        return tex_error("write error");
    return 0;
}

/* ---- lookup ---- */

/* t as the stops take it: NaN and below 0 are 0, above 1 is 1 */
static inline float stop_t(float t)
{
    return !(t >= 0.0f) ? 0.0f : t > 1.0f ? 1.0f : t;
}

/* The first stop with pos > t, by halving */
static int stop_after(const tex_palette *p, float t)
{
    int lo = 0, hi = p->nstops;

    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (p->stops[mid].pos <= t)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The colour at t, whose first stop with pos > t is stops[lo], up to the colour space: 0
 * with rgba made, or 1 with a colour mixed in OKLab, in lab, and its alpha in rgba[3] */
static int mix_stops(const tex_palette *p, float t, int lo, float rgba[4], float lab[3])
{
    const struct tex_palette_stop *a, *b;
    float f;

    if (lo == 0 || lo == p->nstops) {
        memcpy(rgba, p->stops[lo ? lo - 1 : 0].rgba, 4 * sizeof *rgba);
        return 0;
    }
    a = &p->stops[lo - 1];
    b = &p->stops[lo];
    f = (t - a->pos) / (b->pos - a->pos);
    if (f <= 0.0f) { /* exactly at a stop */
        memcpy(rgba, a->rgba, 4 * sizeof *rgba);
        return 0;
    }
    if (p->space == TEX_SPACE_RGB) {
        for (int c = 0; c < 4; c++)
            rgba[c] = a->rgba[c] + f * (b->rgba[c] - a->rgba[c]);
        return 0;
    }
    for (int c = 0; c < 3; c++)
        lab[c] = a->lab[c] + f * (b->lab[c] - a->lab[c]);
    rgba[3] = a->rgba[3] + f * (b->rgba[3] - a->rgba[3]);
    return 1;
}

/* tex_palette_lookup up to the colour space, as mix_stops */
static int lookup_lab(const tex_palette *p, float t, float rgba[4], float lab[3])
{
    t = stop_t(t);
    return mix_stops(p, t, stop_after(p, t), rgba, lab);
}

void tex_palette_lookup(const tex_palette *p, float t, float rgba[4])
{
    float lab[3];
    if (lookup_lab(p, t, rgba, lab))
        tex_oklab_to_srgb(lab, rgba);
}

void tex_palette_index_n(const tex_palette *p, int id, int n, float rgba[4])
{
    int lo = 0, hi = p->nindex - 1;
    double t;

    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (p->index[mid].id == id) {
            memcpy(rgba, p->index[mid].rgba, 4 * sizeof *rgba);
            return;
        }
        if (p->index[mid].id < id)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    if (n >= 1 && id >= 1 && id <= n)
        t = n == 1 ? 0.5 : (double)(id - 1) / (n - 1);
    else {
        t = fmod((double)id * 0.6180339887498949, 1.0);
        if (t < 0)
            t += 1.0;
    }
    tex_palette_lookup(p, (float)t, rgba);
}

void tex_palette_index(const tex_palette *p, int id, float rgba[4])
{
    tex_palette_index_n(p, id, 0, rgba);
}

/* ---- colouring maps ---- */

static inline float palette_t(double v, double lo, double hi, enum tex_outside outside)
{
    double t = hi > lo ? (v - lo) / (hi - lo) : 0.0;

    if (!isfinite(t))
        return 0.0f;
    if (t < 0.0 || t > 1.0) {
        switch (outside) {
        case TEX_OUTSIDE_REPEAT:
            t -= floor(t);
            break;
        case TEX_OUTSIDE_MIRROR:
            t = fmod(fabs(t), 2.0);
            t = t > 1.0 ? 2.0 - t : t;
            break;
        default:
            t = t < 0.0 ? 0.0 : 1.0;
        }
    }
    return (float)t;
}

float tex_palette_t(double v, double lo, double hi, enum tex_outside outside)
{
    return palette_t(v, lo, hi, outside);
}

/* Up to this many stops in order, the first with pos > t is the count of those with
 * pos <= t: no branches to guess wrong on a noisy map, as halving has */
enum { COUNTED_STOPS = 32 };
static int stops_counted(const tex_palette *p)
{
    if (p->nstops > COUNTED_STOPS)
        return 0;
    for (int i = 1; i < p->nstops; i++)
        if (!(p->stops[i].pos >= p->stops[i - 1].pos))
            return 0;
    return 1;
}

/* p's stops in lanes for the AVX-512 or AVX2 kernel, when the CPU has one and they fit: 1 */
static int palette_lanes(const tex_palette *p, struct tex_palette_lanes *l)
{
#ifdef TEX_X86
    if (tex_simd_level() < TEX_SIMD_AVX2 || p->nstops < 1 || p->nstops > 16)
        return 0;
    memset(l, 0, sizeof *l);
    l->n = p->nstops;
    l->oklab = p->space != TEX_SPACE_RGB;
    for (int i = 0; i < p->nstops; i++) {
        l->pos[i] = p->stops[i].pos;
        for (int k = 0; k < 4; k++)
            l->rgba[k][i] = p->stops[i].rgba[k];
        for (int k = 0; k < 3; k++)
            l->lab[k][i] = p->stops[i].lab[k];
    }
    pthread_once(&enc_once, enc_setup);
    return 1;
#else
    (void)p, (void)l;
    return 0;
#endif
}

/* n values of v coloured into out (nc channels each): tex_palette_lookup's colours, those
 * mixed in OKLab taken to sRGB together (oklab_srgb_n); where the CPU has AVX-512 and the
 * palette fits its lanes (l), sixteen at a time with the same floats */
enum { COLOUR_RUN = 256 };
static void colour_run(const tex_palette *p, int counted, const struct tex_palette_lanes *l,
                       const float *v, int n, double lo, double hi, enum tex_outside outside,
                       float *out, int nc)
{
    float c[COLOUR_RUN][4], lab[3][COLOUR_RUN], rgb[3][COLOUR_RUN], t[COLOUR_RUN];
    int at[COLOUR_RUN], after[COLOUR_RUN], k = 0; /* at: the pixels mixed in OKLab */

#ifdef TEX_X86
    if (l) {
        int done = tex_simd_level() >= TEX_SIMD_AVX512
                       ? tex_palette_colour_avx512(l, &enc, v, n, lo, hi, (int)outside, out, nc)
                       : tex_palette_colour_avx2(l, &enc, v, n, lo, hi, (int)outside, out, nc);
        v += done, out += (size_t)done * nc, n -= done;
    }
#else
    (void)l;
#endif
    for (int j = 0; j < n; j++)
        t[j] = stop_t(palette_t(v[j], lo, hi, outside));
    if (counted) {
        for (int j = 0; j < n; j++) {
            int a = 0;
            for (int i = 0; i < p->nstops; i++)
                a += p->stops[i].pos <= t[j];
            after[j] = a;
        }
    } else {
        for (int j = 0; j < n; j++)
            after[j] = stop_after(p, t[j]);
    }
    for (int j = 0; j < n; j++) {
        float e[3];
        if (mix_stops(p, t[j], after[j], c[j], e)) {
            lab[0][k] = e[0], lab[1][k] = e[1], lab[2][k] = e[2];
            at[k++] = j;
        }
    }
    oklab_srgb_n((const float *const[3]){lab[0], lab[1], lab[2]},
                 (float *const[3]){rgb[0], rgb[1], rgb[2]}, k);
    for (int q = 0; q < k; q++)
        c[at[q]][0] = rgb[0][q], c[at[q]][1] = rgb[1][q], c[at[q]][2] = rgb[2][q];
    if (nc == 3) /* a call to memcpy a pixel was a quarter of the time */
        for (int j = 0; j < n; j++)
            out[3 * j] = c[j][0], out[3 * j + 1] = c[j][1], out[3 * j + 2] = c[j][2];
    else
        memcpy(out, c, (size_t)n * sizeof *c);
}

void tex_palette_lookup_n(const tex_palette *p, const float *t, int n, float *rgb)
{
    /* t in [0, 1] is palette_t's own at lo 0, hi 1: (t - 0) / 1 */
    int counted = stops_counted(p);
    struct tex_palette_lanes lanes;
    const struct tex_palette_lanes *l = counted && palette_lanes(p, &lanes) ? &lanes : NULL;
    for (int i = 0; i < n; i += COLOUR_RUN)
        colour_run(p, counted, l, t + i, n - i < COLOUR_RUN ? n - i : COLOUR_RUN, 0, 1,
                   TEX_OUTSIDE_CLAMP, rgb + (size_t)3 * i, 3);
}

tex_map *tex_palette_map(const tex_palette *p, const tex_map *m, double lo, double hi,
                         enum tex_outside outside)
{
    int alpha = 0, nc;
    size_t n = (size_t)m->w * m->h;
    tex_map *out;

    if (m->nc != 1) {
        tex_error("the map has %d channels: a palette colours a scalar map (1 channel) or a "
                  "region-id map", m->nc);
        return NULL;
    }
    for (int i = 0; i < p->nstops; i++)
        alpha |= p->stops[i].rgba[3] != 1.0f;
    for (int i = 0; i < p->nindex; i++)
        alpha |= p->index[i].rgba[3] != 1.0f;
    nc = alpha ? 4 : 3;
    if (!(out = tex_map_new_unset(m->w, m->h, nc))) /* every pixel coloured below */
        return NULL;
    if (m->history && tex_map_set_history(out, m->history) < 0) {
        tex_map_free(out);
        return NULL;
    }
    if (m->subregions > 0) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++) {
            float v = m->px[i], c[4];
            int id = isfinite(v) && fabsf(v) < (float)MAX_ID ? (int)lrintf(v) : 0;
            tex_palette_index_n(p, id, m->subregions, c);
            memcpy(out->px + i * nc, c, nc * sizeof *c);
        }
        return out;
    }
    if (isnan(lo) || isnan(hi)) {
        struct tex_stats_acc a;
        struct tex_stats s;
        tex_stats_begin(&a);
        tex_stats_add_range(&a, m->px, (size_t)m->w, (size_t)m->h, m->nc);
        tex_stats_end(&a, &s);
        lo = s.min;
        hi = s.max;
    }
    int counted = stops_counted(p);
    struct tex_palette_lanes lanes;
    const struct tex_palette_lanes *l = counted && palette_lanes(p, &lanes) ? &lanes : NULL;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i += COLOUR_RUN)
        colour_run(p, counted, l, m->px + i, n - i < COLOUR_RUN ? (int)(n - i) : COLOUR_RUN, lo,
                   hi, outside, out->px + i * nc, nc);
    return out;
}

float *tex_palette_region_colours(const tex_palette *p, int n)
{
    float *c = malloc(sizeof *c * 3 * (n > 0 ? n : 1));
    if (!c) {
        tex_error("out of memory");
        return NULL;
    }
    for (int k = 0; k < n; k++) {
        float rgba[4];
        tex_palette_index_n(p, k + 1, n, rgba);
        for (int j = 0; j < 3; j++)
            c[3 * k + j] = rgba[j];
    }
    return c;
}
