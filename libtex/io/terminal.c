/* terminal.c - a map drawn in a terminal: sixel or kitty graphics (see terminal.h) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "io/terminal.h"

enum tex_terminal_proto tex_terminal_guess(void)
{
    const char *term = getenv("TERM"), *kitty = getenv("KITTY_WINDOW_ID");
    if ((kitty && *kitty) || (term && (strstr(term, "kitty") || strstr(term, "ghostty"))))
        return TEX_TERMINAL_KITTY;
    return TEX_TERMINAL_SIXEL;
}

/* Pixel (x, y) as 8-bit RGB: clamped display values, grey repeated, alpha over black. */
static void rgb8(const tex_map *m, int x, int y, unsigned char out[3])
{
    const float *p = tex_map_px(m, x, y);
    float c[3], a = m->nc == 4 ? p[3] : 1;
    for (int k = 0; k < 3; k++)
        c[k] = m->nc >= 3 ? p[k] : m->nc == 2 ? (k < 2 ? p[k] : 0) : p[0];
    for (int k = 0; k < 3; k++) {
        float v = c[k] * (a > 0 ? (a < 1 ? a : 1) : 0);
        v = v > 0 ? (v < 1 ? v : 1) : 0; /* NaN: 0 */
        out[k] = (unsigned char)(v * 255 + 0.5f);
    }
}

/* Median cut: the pixels' colours split, box by box, at the median of the widest channel
 * of the box whose range is widest, until there are at most 256 boxes; each register
 * is its box's mean.  idx holds the n pixels' indices into rgb (reordered).  Returns
 * the number of registers in pal (3 bytes each). */
struct box { int lo, hi, axis, range; };

/* idx[lo..hi) in order of their channel axis, by counting (no state beyond the call, as
 * qsort's comparison would need); tmp holds hi - lo ints */
static void sort_by(int *idx, int lo, int hi, int axis, const unsigned char *rgb, int *tmp)
{
    int count[257] = {0};
    for (int i = lo; i < hi; i++)
        count[rgb[idx[i] * 3 + axis] + 1]++;
    for (int v = 0; v < 256; v++)
        count[v + 1] += count[v];
    for (int i = lo; i < hi; i++)
        tmp[count[rgb[idx[i] * 3 + axis]]++] = idx[i];
    memcpy(idx + lo, tmp, (size_t)(hi - lo) * sizeof *idx);
}

static void box_measure(struct box *b, const int *idx, const unsigned char *rgb)
{
    int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
    for (int i = b->lo; i < b->hi; i++)
        for (int k = 0; k < 3; k++) {
            int v = rgb[idx[i] * 3 + k];
            lo[k] = v < lo[k] ? v : lo[k], hi[k] = v > hi[k] ? v : hi[k];
        }
    b->axis = 0;
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[b->axis] - lo[b->axis])
            b->axis = k;
    b->range = hi[b->axis] - lo[b->axis];
}

static int median_cut(const unsigned char *rgb, int *idx, int *tmp, int n, unsigned char *pal)
{
    struct box box[256] = {{0, n, 0, 0}};
    int nb = 1;

    box_measure(&box[0], idx, rgb);
    while (nb < 256) {
        int w = -1;
        for (int i = 0; i < nb; i++) /* the widest box that can split */
            if (box[i].range > 0 && (w < 0 || box[i].range > box[w].range))
                w = i;
        if (w < 0)
            break;
        sort_by(idx, box[w].lo, box[w].hi, box[w].axis, rgb, tmp);
        int mid = box[w].lo + (box[w].hi - box[w].lo) / 2;
        /* the cut between two values, so equal colours stay in one box */
        unsigned char v = rgb[idx[mid] * 3 + box[w].axis];
        while (mid > box[w].lo && rgb[idx[mid - 1] * 3 + box[w].axis] == v)
            mid--;
        if (mid == box[w].lo)
            while (mid < box[w].hi && rgb[idx[mid] * 3 + box[w].axis] == v)
                mid++;
        box[nb] = (struct box){mid, box[w].hi, 0, 0};
        box[w].hi = mid;
        box_measure(&box[w], idx, rgb);
        box_measure(&box[nb++], idx, rgb);
    }
    for (int i = 0; i < nb; i++) {
        double sum[3] = {0, 0, 0};
        for (int j = box[i].lo; j < box[i].hi; j++)
            for (int k = 0; k < 3; k++)
                sum[k] += rgb[idx[j] * 3 + k];
        for (int k = 0; k < 3; k++)
            pal[i * 3 + k] = (unsigned char)(sum[k] / (box[i].hi - box[i].lo) + 0.5);
    }
    return nb;
}

/* The register nearest to colour c (Euclidean in 8-bit RGB; the first of equals) */
static int nearest(const float c[3], const unsigned char *pal, int np)
{
    int best = 0;
    float bd = 1e30f;
    for (int i = 0; i < np; i++) {
        float dr = c[0] - pal[i * 3], dg = c[1] - pal[i * 3 + 1], db = c[2] - pal[i * 3 + 2];
        float d = dr * dr + dg * dg + db * db;
        if (d < bd)
            bd = d, best = i;
    }
    return best;
}

/* Each pixel's register into reg, Floyd-Steinberg's error carried to its neighbours;
 * err holds two rows of 3 floats per pixel and a pixel each side. */
static void diffuse(const tex_map *m, const unsigned char *rgb, const unsigned char *pal, int np,
                    unsigned char *reg, float *err)
{
    size_t row = (size_t)(m->w + 2) * 3;
    float *cur = err, *next = err + row;

    memset(err, 0, 2 * row * sizeof *err);
    for (int y = 0; y < m->h; y++) {
        memset(next, 0, row * sizeof *next);
        for (int x = 0; x < m->w; x++) {
            const unsigned char *p = rgb + ((size_t)y * m->w + x) * 3;
            float c[3], *e = cur + (size_t)(x + 1) * 3, *en = next + (size_t)(x + 1) * 3;
            for (int k = 0; k < 3; k++) {
                c[k] = p[k] + e[k];
                c[k] = c[k] < 0 ? 0 : c[k] > 255 ? 255 : c[k];
            }
            int r = nearest(c, pal, np);
            reg[(size_t)y * m->w + x] = (unsigned char)r;
            for (int k = 0; k < 3; k++) {
                float d = c[k] - pal[r * 3 + k];
                e[k + 3] += d * 7 / 16;
                en[k - 3] += d * 3 / 16;
                en[k] += d * 5 / 16;
                en[k + 3] += d * 1 / 16;
            }
        }
        float *t = cur;
        cur = next, next = t;
    }
}

static void sixel_run(FILE *fp, int ch, int n)
{
    if (n > 3)
        fprintf(fp, "!%d%c", n, 63 + ch);
    else
        while (n--)
            putc(63 + ch, fp);
}

static int sixel(FILE *fp, const tex_map *m, unsigned char *rgb)
{
    size_t n = (size_t)m->w * m->h;
    unsigned char pal[256 * 3], *reg = malloc(n);
    int *idx = malloc(2 * n * sizeof *idx), np; /* and the sort's room after it */
    float *err = malloc((size_t)(m->w + 2) * 6 * sizeof *err);

    if (!reg || !idx || !err) {
        free(reg), free(idx), free(err);
        return tex_error("out of memory");
    }
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            rgb8(m, x, y, rgb + ((size_t)y * m->w + x) * 3);
    for (size_t i = 0; i < n; i++)
        idx[i] = (int)i;
    np = median_cut(rgb, idx, idx + n, (int)n, pal);
    diffuse(m, rgb, pal, np, reg, err);
    free(idx), free(err);
    fputs("\033Pq\"1;1;", fp);
    fprintf(fp, "%d;%d", m->w, m->h);
    for (int i = 0; i < np; i++) /* registers in percent */
        fprintf(fp, "#%d;2;%d;%d;%d", i, (pal[i * 3] * 100 + 127) / 255,
                (pal[i * 3 + 1] * 100 + 127) / 255, (pal[i * 3 + 2] * 100 + 127) / 255);
    for (int y0 = 0; y0 < m->h; y0 += 6) { /* a band of six rows */
        int rows = m->h - y0 < 6 ? m->h - y0 : 6;
        char used[256] = {0};
        for (int j = 0; j < rows; j++)
            for (int x = 0; x < m->w; x++)
                used[reg[(size_t)(y0 + j) * m->w + x]] = 1;
        int first = 1;
        for (int r = 0; r < np; r++) {
            if (!used[r])
                continue;
            if (!first)
                putc('$', fp); /* back to the band's start for the next colour */
            first = 0;
            fprintf(fp, "#%d", r);
            int run = 0, prev = -1;
            for (int x = 0; x < m->w; x++) {
                int bits = 0;
                for (int j = 0; j < rows; j++)
                    bits |= (reg[(size_t)(y0 + j) * m->w + x] == r) << j;
                if (bits != prev && run)
                    sixel_run(fp, prev, run), run = 0;
                prev = bits;
                run++;
            }
            sixel_run(fp, prev, run);
        }
        putc('-', fp); /* the next band */
    }
    fputs("\033\\", fp);
    free(reg);
    return 0;
}

static void kitty(FILE *fp, const tex_map *m, unsigned char *rgb)
{
    static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t n = (size_t)m->w * m->h * 3;
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            rgb8(m, x, y, rgb + ((size_t)y * m->w + x) * 3);
    /* base64 in chunks of 4096 characters (3072 bytes), m=1 on all but the last */
    for (size_t off = 0; off < n; off += 3072) {
        size_t len = n - off < 3072 ? n - off : 3072;
        if (off == 0)
            fprintf(fp, "\033_Ga=T,f=24,s=%d,v=%d,m=%d;", m->w, m->h, off + len < n);
        else
            fprintf(fp, "\033_Gm=%d;", off + len < n);
        for (size_t i = 0; i < len; i += 3) {
            const unsigned char *p = rgb + off + i;
            unsigned v = (unsigned)p[0] << 16 | (i + 1 < len ? p[1] : 0) << 8 | (i + 2 < len ? p[2] : 0);
            putc(b64[v >> 18 & 63], fp);
            putc(b64[v >> 12 & 63], fp);
            putc(i + 1 < len ? b64[v >> 6 & 63] : '=', fp);
            putc(i + 2 < len ? b64[v & 63] : '=', fp);
        }
        fputs("\033\\", fp);
    }
}

int tex_terminal_write(FILE *fp, const tex_map *m, enum tex_terminal_proto proto)
{
    unsigned char *buf = malloc((size_t)m->w * m->h * 3);
    if (!buf)
        return tex_error("out of memory");
    if (proto == TEX_TERMINAL_KITTY) {
        kitty(fp, m, buf);
    } else if (sixel(fp, m, buf) < 0) {
        free(buf);
        return -1;
    }
    free(buf);
    putc('\n', fp);
    if (fflush(fp) != 0 || ferror(fp))
        return tex_error("standard output: write error");
    return 0;
}
