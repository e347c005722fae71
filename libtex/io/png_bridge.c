/* png_bridge.c - PNG through libpng, built as textura-png.so (see codec_bridge.h)
 *
 * Values are read as stored: gAMA, sRGB, iCCP and cHRM are ignored (libpng
 * applies no gamma unless asked), palettes and tRNS are expanded, and
 * grey+alpha stays two channels, not premultiplied.
 */
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <png.h>

#include "io/codec_bridge.h"

/* The largest ratio of inflated to deflated bytes deflate allows (258-byte
 * matches in 2 bits each): a PNG declaring more pixel bytes than this many
 * times its own size cannot be valid, and is refused before allocation. */
#define DEFLATE_MAX_RATIO 1032

struct ctx {
    const unsigned char *p;
    size_t len, off;
    char *err;
    size_t errlen;
    jmp_buf jb;
};

static void on_error(png_structp png, png_const_charp msg)
{
    struct ctx *c = png_get_error_ptr(png);
    snprintf(c->err, c->errlen, "%s", msg);
    longjmp(c->jb, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

static void read_mem(png_structp png, png_bytep dst, size_t n)
{
    struct ctx *c = png_get_io_ptr(png);
    if (n > c->len - c->off)
        png_error(png, "truncated PNG data");
    memcpy(dst, c->p + c->off, n);
    c->off += n;
}

/* Read the header and set the transforms; returns the channels read. */
static int start(png_structp png, png_infop info, struct ctx *c, int *w, int *h, int *depth)
{
    png_uint_32 pw, ph;
    int bd, ct, il;
    unsigned long long bytes;

    png_set_read_fn(png, c, read_mem);
    png_set_user_limits(png, 65536, 65536);
    png_set_chunk_malloc_max(png, 8u << 20);
    png_read_info(png, info);
    png_get_IHDR(png, info, &pw, &ph, &bd, &ct, &il, NULL, NULL);
    bytes = ((unsigned long long)pw * png_get_channels(png, info) * (unsigned)bd + 7) / 8 * ph;
    if (bytes / DEFLATE_MAX_RATIO > c->len) {
        snprintf(c->err, c->errlen, "PNG declares %lux%lu pixels, more than its %zu bytes can hold",
                 (unsigned long)pw, (unsigned long)ph, c->len);
        longjmp(c->jb, 1);
    }
    png_set_expand(png);
    if (bd == 16 && *(const unsigned char *)&(uint16_t){1})
        png_set_swap(png);
    if (il != PNG_INTERLACE_NONE)
        png_set_interlace_handling(png);
    png_read_update_info(png, info);
    *w = (int)pw;
    *h = (int)ph;
    *depth = png_get_bit_depth(png, info);
    return png_get_channels(png, info);
}

static int b_info(const void *mem, size_t len, int *w, int *h, int *nc, char *err, size_t errlen)
{
    struct ctx c = {.p = mem, .len = len, .err = err, .errlen = errlen};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &c, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    int depth, r = -1;

    if (!info) {
        snprintf(err, errlen, "out of memory");
    } else if (!setjmp(c.jb)) {
        *nc = start(png, info, &c, w, h, &depth);
        r = 0;
    }
    png_destroy_read_struct(&png, &info, NULL);
    return r;
}

static int b_read(const void *mem, size_t len, float *px, char *err, size_t errlen)
{
    struct ctx c = {.p = mem, .len = len, .err = err, .errlen = errlen};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &c, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile img = NULL;
    png_bytep *volatile rows = NULL;
    int r = -1;

    if (!info) {
        snprintf(err, errlen, "out of memory");
    } else if (!setjmp(c.jb)) {
        int w, h, depth, nc = start(png, info, &c, &w, &h, &depth);
        size_t rb = png_get_rowbytes(png, info), n = (size_t)w * nc;
        float lut[256];
        for (int v = 0; v < 256; v++)
            lut[v] = (float)v / 255.0f;
        img = malloc(rb * (size_t)h);
        rows = malloc(sizeof *rows * (size_t)h);
        if (!img || !rows)
            png_error(png, "out of memory");
        for (int y = 0; y < h; y++)
            rows[y] = img + rb * (size_t)y;
        png_read_image(png, rows);
        for (int y = 0; y < h; y++) {
            float *d = px + (size_t)y * n;
            if (depth == 8)
                for (size_t i = 0; i < n; i++)
                    d[i] = lut[rows[y][i]];
            else
                for (size_t i = 0; i < n; i++)
                    d[i] = (float)((const uint16_t *)rows[y])[i] / 65535.0f;
        }
        r = 0;
    }
    free(img);
    free(rows);
    png_destroy_read_struct(&png, &info, NULL);
    return r;
}

/* Rows are asked for TEX_CODEC_BAND at a time and written one by one (png_write_image is
 * png_write_row over the rows: the same bytes). */
static int b_write_rows(int fd, int w, int h, int nc, int bits,
                        int (*rows)(void *arg, int y, int n, void *dst), void *arg, char *err,
                        size_t errlen)
{
    static const int types[] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    struct ctx c = {.err = err, .errlen = errlen};
    int dfd = dup(fd);
    FILE *volatile f = dfd >= 0 ? fdopen(dfd, "wb") : NULL;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &c, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile band = NULL;
    int r = -1;

    if (!f || !info || (bits != 8 && bits != 16) || nc < 1 || nc > 4) {
        snprintf(err, errlen, "%s", !f || !info ? "cannot start the PNG writer" : "bad PNG layout");
        if (!f && dfd >= 0)
            close(dfd);
    } else if (!setjmp(c.jb)) {
        size_t stride = (size_t)w * nc * (bits / 8);
        png_init_io(png, f);
        /* zlib level 2 with the Sub and Up filters: a little larger than level 6 with
         * all five filters, at half its time (doc/performance.md, io/ and cli/). */
        png_set_compression_level(png, 2);
        png_set_filter(png, 0, PNG_FILTER_SUB | PNG_FILTER_UP);
        png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, bits, types[nc],
                     PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        if (bits == 16 && *(const unsigned char *)&(uint16_t){1})
            png_set_swap(png);
        if (!(band = malloc(stride * TEX_CODEC_BAND)))
            png_error(png, "out of memory");
        for (int y = 0; y < h; y += TEX_CODEC_BAND) {
            int n = h - y < TEX_CODEC_BAND ? h - y : TEX_CODEC_BAND;
            if (rows(arg, y, n, band) < 0)
                png_error(png, "rows");
            for (int k = 0; k < n; k++)
                png_write_row(png, band + stride * (size_t)k);
        }
        png_write_end(png, NULL);
        r = 0;
    }
    free(band);
    png_destroy_write_struct(&png, &info);
    if (f && fclose(f) != 0 && r == 0) {
        snprintf(err, errlen, "write error");
        r = -1;
    }
    return r;
}

static int b_write(int fd, const void *px, int w, int h, int nc, int bits, char *err,
                   size_t errlen)
{
    struct tex_codec_px p = {px, (size_t)w * nc * (bits / 8)};
    return b_write_rows(fd, w, h, nc, bits, tex_codec_copy_rows, &p, err, errlen);
}

__attribute__((visibility("default"))) const struct tex_codec_bridge tex_png_bridge = {
    TEX_CODEC_BRIDGE_VERSION, b_info, b_read, b_write, b_write_rows};
