/* netpbm.c - PNM, PAM and PFM without a library (see netpbm.h) */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"
#include "io/limit.h"
#include "io/netpbm.h"
#include "io/stream.h"

/* Sides are judged by tex_map_check_size, as for every format (a usage
 * error naming the limit); the parser only keeps them from overflowing. */
#define SIDE_ANY (1L << 40)

struct cur {
    const unsigned char *p, *end;
    const char *name;
};

static int is_ws(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* Skip white space and '#' comments (to the end of their line). */
static void skip_ws(struct cur *c)
{
    while (c->p < c->end) {
        if (*c->p == '#')
            while (c->p < c->end && *c->p != '\n' && *c->p != '\r')
                c->p++;
        else if (is_ws(*c->p))
            c->p++;
        else
            break;
    }
}

/* A decimal header number in [lo, hi]; what names it in the message. */
static int header_num(struct cur *c, const char *what, long lo, long hi, long *out)
{
    const unsigned char *start;
    long v = 0;

    skip_ws(c);
    start = c->p;
    while (c->p < c->end && *c->p >= '0' && *c->p <= '9') {
        if (v <= hi)
            v = v * 10 + (*c->p - '0');
        c->p++;
    }
    if (c->p == start)
        return tex_error("%s: %s", c->name, c->p < c->end ? "bad PNM header (a number expected)"
                                                          : "truncated PNM header");
    if (hi == SIDE_ANY && v > hi)
        return tex_usage_error("%s: %s %.*s is out of range: each side must be 1..%d", c->name,
                               what, (int)(c->p - start > 12 ? 12 : c->p - start),
                               (const char *)start, TEX_MAP_MAX_SIDE);
    if (v < lo || v > hi)
        return tex_error("%s: %s %.*s is not %ld..%ld", c->name, what,
                         (int)(c->p - start > 12 ? 12 : c->p - start), (const char *)start, lo, hi);
    *out = v;
    return 0;
}

static tex_map *new_map(long w, long h, int nc, const char *name)
{
    tex_map *m;

    if (tex_map_check_size(w, h, nc) < 0 || tex_input_check_decoded(w, h, nc) < 0 ||
        !(m = tex_map_new((int)w, (int)h, nc))) {
        tex_error_context(name);
        return NULL;
    }
    return m;
}

/* Raw samples (1 or 2 bytes, big-endian) of maxval mv into m. */
static int read_raw(struct cur *c, tex_map *m, long mv)
{
    size_t n = tex_map_samples(m), bytes = mv > 255 ? 2 : 1;
    float lut[256];

    if ((size_t)(c->end - c->p) / bytes < n)
        return tex_error("%s: truncated PNM data (%zu of %zu bytes)", c->name,
                         (size_t)(c->end - c->p), n * bytes);
    if (bytes == 1) {
        for (int v = 0; v < 256; v++)
            lut[v] = (float)v / (float)mv;
        for (size_t i = 0; i < n; i++) {
            if (c->p[i] > mv)
                return tex_error("%s: sample %d exceeds maxval %ld", c->name, c->p[i], mv);
            m->px[i] = lut[c->p[i]];
        }
    } else {
        for (size_t i = 0; i < n; i++) {
            unsigned v = (unsigned)c->p[2 * i] << 8 | c->p[2 * i + 1];
            if (v > (unsigned long)mv)
                return tex_error("%s: sample %u exceeds maxval %ld", c->name, v, mv);
            m->px[i] = (float)v / (float)mv;
        }
    }
    c->p += n * bytes;
    return 0;
}

/* Plain (ASCII) samples; for PBM (mv 0) the digits need no separator. */
static int read_plain(struct cur *c, tex_map *m, long mv)
{
    size_t n = tex_map_samples(m);

    for (size_t i = 0; i < n; i++) {
        long v;
        if (mv == 0) {
            skip_ws(c);
            if (c->p >= c->end || (*c->p != '0' && *c->p != '1'))
                return tex_error("%s: %s PBM data", c->name, c->p < c->end ? "bad" : "truncated");
            m->px[i] = *c->p++ == '1' ? 0.0f : 1.0f;
            continue;
        }
        if (c->p >= c->end)
            return tex_error("%s: truncated PNM data", c->name);
        if (header_num(c, "sample", 0, mv, &v) < 0)
            return -1;
        m->px[i] = (float)v / (float)mv;
    }
    return 0;
}

static int read_pbm_raw(struct cur *c, tex_map *m)
{
    size_t stride = ((size_t)m->w + 7) / 8;

    if ((size_t)(c->end - c->p) / stride < (size_t)m->h)
        return tex_error("%s: truncated PBM data", c->name);
    for (int y = 0; y < m->h; y++, c->p += stride) {
        float *row = tex_map_row(m, y);
        for (int x = 0; x < m->w; x++)
            row[x] = c->p[x >> 3] >> (7 - (x & 7)) & 1 ? 0.0f : 1.0f;
    }
    return 0;
}

/* The header of a PAM after "P7": WIDTH HEIGHT DEPTH MAXVAL [TUPLTYPE] ENDHDR. */
static int pam_header(struct cur *c, long *w, long *h, long *depth, long *mv)
{
    *w = *h = *depth = *mv = -1;
    for (;;) {
        const unsigned char *k;
        size_t kl;
        skip_ws(c);
        if (c->p >= c->end)
            return tex_error("%s: truncated PAM header", c->name);
        for (k = c->p; c->p < c->end && !is_ws(*c->p); c->p++)
            ;
        kl = (size_t)(c->p - k);
#define KEY(s) (kl == sizeof s - 1 && memcmp(k, s, kl) == 0)
        if (KEY("ENDHDR")) {
            if (c->p < c->end && *c->p == '\r')
                c->p++;
            if (c->p >= c->end || *c->p != '\n')
                return tex_error("%s: truncated PAM header", c->name);
            c->p++;
            break;
        } else if (KEY("WIDTH")) {
            if (header_num(c, "PAM width", 0, SIDE_ANY, w) < 0)
                return -1;
        } else if (KEY("HEIGHT")) {
            if (header_num(c, "PAM height", 0, SIDE_ANY, h) < 0)
                return -1;
        } else if (KEY("DEPTH")) {
            if (header_num(c, "PAM depth", 1, 4, depth) < 0)
                return -1;
        } else if (KEY("MAXVAL")) {
            if (header_num(c, "PAM maxval", 1, 65535, mv) < 0)
                return -1;
        } else if (KEY("TUPLTYPE")) {
            /* The depth decides the channels; the type's words are only a label. */
            while (c->p < c->end && *c->p != '\n')
                c->p++;
        } else {
            return tex_error("%s: unknown PAM header line '%.*s'", c->name, (int)(kl > 20 ? 20 : kl),
                             (const char *)k);
        }
#undef KEY
    }
    if (*w < 0 || *h < 0 || *depth < 0 || *mv < 0)
        return tex_error("%s: PAM header lacks %s", c->name,
                         *w < 0 ? "WIDTH" : *h < 0 ? "HEIGHT" : *depth < 0 ? "DEPTH" : "MAXVAL");
    return 0;
}

static tex_map *decode_pfm(struct cur *c, int nc)
{
    long w, h;
    double scale;
    char num[64], *e;
    size_t k = 0, row;
    tex_map *m;
    int little;

    if (header_num(c, "PFM width", 0, SIDE_ANY, &w) < 0 ||
        header_num(c, "PFM height", 0, SIDE_ANY, &h) < 0)
        return NULL;
    skip_ws(c);
    while (c->p < c->end && !is_ws(*c->p) && k < sizeof num - 1)
        num[k++] = (char)*c->p++;
    num[k] = '\0';
    scale = strtod(num, &e);
    if (!k || *e || scale == 0.0 || !isfinite(scale) || c->p >= c->end || !is_ws(*c->p)) {
        tex_error("%s: bad PFM scale '%s' (a non-zero number)", c->name, num);
        return NULL;
    }
    c->p++; /* the single white-space character before the data */
    little = scale < 0;
    if (!(m = new_map(w, h, nc, c->name)))
        return NULL;
    row = (size_t)w * nc;
    if ((size_t)(c->end - c->p) / (row * 4) < (size_t)h) {
        tex_error("%s: truncated PFM data", c->name);
        tex_map_free(m);
        return NULL;
    }
    for (long y = h - 1; y >= 0; y--, c->p += row * 4) {
        float *d = tex_map_row(m, (int)y);
        for (size_t i = 0; i < row; i++) {
            const unsigned char *b = c->p + 4 * i;
            uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                                      (uint32_t)b[3] << 24
                                : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 |
                                      (uint32_t)b[0] << 24;
            memcpy(d + i, &u, 4);
        }
    }
    return m;
}

tex_map *tex_netpbm_decode(const void *data, size_t len, const char *name)
{
    struct cur c = {data, (const unsigned char *)data + len, name};
    long w, h, nc = 1, mv = 1;
    tex_map *m;
    char kind;
    int r;

    if (len < 3 || c.p[0] != 'P' || !is_ws(c.p[2]) || !strchr("1234567Ff", c.p[1])) {
        tex_error("%s: not a PNM, PAM or PFM file", name);
        return NULL;
    }
    kind = (char)c.p[1];
    c.p += 2;
    if (kind == 'F' || kind == 'f')
        return decode_pfm(&c, kind == 'F' ? 3 : 1);
    if (kind == '7') {
        if (pam_header(&c, &w, &h, &nc, &mv) < 0)
            return NULL;
    } else {
        if (header_num(&c, "PNM width", 0, SIDE_ANY, &w) < 0 ||
            header_num(&c, "PNM height", 0, SIDE_ANY, &h) < 0)
            return NULL;
        if (kind != '1' && kind != '4' && header_num(&c, "PNM maxval", 1, 65535, &mv) < 0)
            return NULL;
        if (kind == '3' || kind == '6')
            nc = 3;
        /* One white-space character separates a raw header from its data. */
        if (kind >= '4') {
            if (c.p >= c.end || !is_ws(*c.p)) {
                tex_error("%s: truncated PNM header", name);
                return NULL;
            }
            c.p++;
        }
    }
    if (!(m = new_map(w, h, (int)nc, name)))
        return NULL;
    if (kind == '4')
        r = read_pbm_raw(&c, m);
    else if (kind == '1')
        r = read_plain(&c, m, 0);
    else if (kind <= '3')
        r = read_plain(&c, m, mv);
    else
        r = read_raw(&c, m, mv);
    if (r < 0) {
        tex_map_free(m);
        return NULL;
    }
    return m;
}

/* ---- writing ---- */

static unsigned quant(float v, float scale)
{
    v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN fails v > 0 */
    return (unsigned)lrintf(v * scale);
}

/* Rows go out through one buffer of about 256 KiB. */
static int write_rows(const tex_map *m, int fd, int depth, enum tex_pnm_variant v,
                      const char *name)
{
    size_t per_row = v == TEX_PNM_PBM ? ((size_t)m->w + 7) / 8 : (size_t)m->w * m->nc * (depth / 8);
    size_t rows = per_row >= (1 << 18) ? 1 : (1 << 18) / per_row, fill = 0;
    unsigned char *buf = malloc(rows * per_row);
    float scale = depth == 16 ? 65535.0f : 255.0f;
    int r = 0;

    if (!buf)
        return tex_error("out of memory");
    for (int y = 0; y < m->h && r == 0; y++) {
        const float *s = tex_map_row(m, y);
        unsigned char *d = buf + fill;
        if (v == TEX_PNM_PBM) {
            memset(d, 0, per_row);
            for (int x = 0; x < m->w; x++) {
                const float *p = s + (size_t)x * m->nc;
                float g = m->nc >= 3 ? (p[0] + p[1] + p[2]) / 3.0f : p[0];
                if (!(g >= 0.5f))
                    d[x >> 3] |= (unsigned char)(0x80 >> (x & 7));
            }
        } else if (depth == 8) {
            for (size_t i = 0, n = (size_t)m->w * m->nc; i < n; i++)
                d[i] = (unsigned char)quant(s[i], scale);
        } else {
            for (size_t i = 0, n = (size_t)m->w * m->nc; i < n; i++) {
                unsigned q = quant(s[i], scale);
                d[2 * i] = (unsigned char)(q >> 8);
                d[2 * i + 1] = (unsigned char)q;
            }
        }
        fill += per_row;
        if (fill + per_row > rows * per_row || y == m->h - 1) {
            r = tex_write_all(fd, buf, fill, name);
            fill = 0;
        }
    }
    free(buf);
    return r;
}

int tex_pnm_write_head(int w, int h, int nc, int fd, int depth, enum tex_pnm_variant v,
                       const char *name)
{
    static const char *const tupl[] = {"", "GRAYSCALE", "GRAYSCALE_ALPHA", "RGB", "RGB_ALPHA"};
    char head[160];
    int n;

    if (depth != 8 && depth != 16)
        return tex_usage_error("%s: PNM holds 8 or 16-bit samples (got %d)", name, depth);
    if (v == TEX_PNM_PBM)
        n = snprintf(head, sizeof head, "P4\n%d %d\n", w, h);
    else if (v == TEX_PNM_PAM)
        n = snprintf(head, sizeof head, "P7\nWIDTH %d\nHEIGHT %d\nDEPTH %d\nMAXVAL %d\nTUPLTYPE %s\nENDHDR\n",
                     w, h, nc, depth == 16 ? 65535 : 255, tupl[nc]);
    else if (nc == 1 || nc == 3)
        n = snprintf(head, sizeof head, "P%c\n%d %d\n%d\n", nc == 1 ? '5' : '6', w, h,
                     depth == 16 ? 65535 : 255);
    else
        return tex_error("%s: PNM holds 1 or 3 channels (got %d)", name, nc);
    return tex_write_all(fd, head, (size_t)n, name);
}

int tex_pnm_write_band(const tex_map *band, int fd, int depth, enum tex_pnm_variant v,
                       const char *name)
{
    return write_rows(band, fd, depth, v, name);
}

int tex_pnm_write_fd(const tex_map *m, int fd, int depth, enum tex_pnm_variant v,
                     const char *name)
{
    if (tex_pnm_write_head(m->w, m->h, m->nc, fd, depth, v, name) < 0)
        return -1;
    return write_rows(m, fd, depth, v, name);
}

int tex_pfm_write_head(int w, int h, int nc, int fd, const char *name)
{
    char head[64];
    int n;

    if (nc != 1 && nc != 3)
        return tex_error("%s: PFM holds 1 or 3 channels (got %d)", name, nc);
    n = snprintf(head, sizeof head, "%s\n%d %d\n-1.0\n", nc == 3 ? "PF" : "Pf", w, h);
    return tex_write_all(fd, head, (size_t)n, name) < 0 ? -1 : n;
}

int tex_pfm_write_band(const tex_map *band, int y, int h, int head, int fd, const char *name)
{
    size_t row = (size_t)band->w * band->nc * sizeof(float);

    for (int k = 0; k < band->h; k++) {
        const char *p = (const char *)tex_map_row(band, k);
        off_t at = (off_t)head + (off_t)(h - 1 - (y + k)) * (off_t)row;
        for (size_t done = 0; done < row;) {
            ssize_t n = pwrite(fd, p + done, row - done, at + (off_t)done);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0)
                return tex_error("%s: write error: %s", name, strerror(errno));
            done += (size_t)n;
        }
    }
    return 0;
}

int tex_pfm_write_fd(const tex_map *m, int fd, const char *name)
{
    int r = tex_pfm_write_head(m->w, m->h, m->nc, fd, name) < 0 ? -1 : 0;
    for (int y = m->h - 1; y >= 0 && r == 0; y--)
        r = tex_write_all(fd, tex_map_row(m, y), (size_t)m->w * m->nc * sizeof(float), name);
    return r;
}
