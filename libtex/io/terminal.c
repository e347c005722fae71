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

/* The register of the 6x6x6 cube nearest to an 8-bit colour */
static int cube(const unsigned char c[3])
{
    int r = (c[0] * 5 + 127) / 255, g = (c[1] * 5 + 127) / 255, b = (c[2] * 5 + 127) / 255;
    return 36 * r + 6 * g + b;
}

static void sixel_run(FILE *fp, int ch, int n)
{
    if (n > 3)
        fprintf(fp, "!%d%c", n, 63 + ch);
    else
        while (n--)
            putc(63 + ch, fp);
}

static void sixel(FILE *fp, const tex_map *m, unsigned char *reg)
{
    fputs("\033Pq\"1;1;", fp);
    fprintf(fp, "%d;%d", m->w, m->h);
    for (int i = 0; i < 216; i++) /* registers in percent */
        fprintf(fp, "#%d;2;%d;%d;%d", i, i / 36 * 20, i / 6 % 6 * 20, i % 6 * 20);
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++) {
            unsigned char c[3];
            rgb8(m, x, y, c);
            reg[(size_t)y * m->w + x] = (unsigned char)cube(c);
        }
    for (int y0 = 0; y0 < m->h; y0 += 6) { /* a band of six rows */
        int rows = m->h - y0 < 6 ? m->h - y0 : 6;
        char used[216] = {0};
        for (int j = 0; j < rows; j++)
            for (int x = 0; x < m->w; x++)
                used[reg[(size_t)(y0 + j) * m->w + x]] = 1;
        int first = 1;
        for (int r = 0; r < 216; r++) {
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
    if (proto == TEX_TERMINAL_KITTY)
        kitty(fp, m, buf);
    else
        sixel(fp, m, buf);
    free(buf);
    putc('\n', fp);
    if (fflush(fp) != 0 || ferror(fp))
        return tex_error("standard output: write error");
    return 0;
}
