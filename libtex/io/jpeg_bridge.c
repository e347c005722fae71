/* jpeg_bridge.c - JPEG through libjpeg-turbo, built as textura-jpeg.so (see codec_bridge.h)
 *
 * Grey and YCbCr/RGB files are read as 1 or 3 channels; CMYK and YCCK are
 * declined (OpenImageIO converts them).  Files are written at quality 95
 * without chroma subsampling: a texture map's colour edges matter.
 */
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <jpeglib.h>
#include <jerror.h>

#include "io/codec_bridge.h"

struct err_mgr {
    struct jpeg_error_mgr pub;
    jmp_buf jb;
    char *err;
    size_t errlen;
};

static void on_error(j_common_ptr j)
{
    struct err_mgr *e = (struct err_mgr *)j->err;
    char msg[JMSG_LENGTH_MAX];
    j->err->format_message(j, msg);
    snprintf(e->err, e->errlen, "%s", msg);
    longjmp(e->jb, 1);
}

/* libjpeg calls a short file a warning and goes on with grey filler; a
 * texture map made of filler is an error.  Other warnings (extraneous
 * bytes before a marker...) are let pass, as every viewer does. */
static void on_message(j_common_ptr j, int level)
{
    if (level < 0 && j->err->msg_code == JWRN_JPEG_EOF)
        on_error(j);
}

static void start(struct jpeg_decompress_struct *d, struct err_mgr *e, char *err, size_t errlen)
{
    memset(d, 0, sizeof *d);
    d->err = jpeg_std_error(&e->pub);
    e->pub.error_exit = on_error;
    e->pub.emit_message = on_message;
    e->err = err;
    e->errlen = errlen;
}

/* Header and colour space: the channels, or TEX_CODEC_DECLINED. */
static int header(struct jpeg_decompress_struct *d, const void *mem, size_t len, char *err,
                  size_t errlen)
{
    jpeg_mem_src(d, mem, (unsigned long)len);
    jpeg_read_header(d, TRUE);
    if (d->jpeg_color_space == JCS_CMYK || d->jpeg_color_space == JCS_YCCK) {
        snprintf(err, errlen, "CMYK JPEG");
        return TEX_CODEC_DECLINED;
    }
    d->out_color_space = d->num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
    return d->num_components == 1 ? 1 : 3;
}

static int b_info(const void *mem, size_t len, int *w, int *h, int *nc, char *err, size_t errlen)
{
    struct jpeg_decompress_struct d;
    struct err_mgr e;
    volatile int r = -1;

    start(&d, &e, err, errlen);
    if (!setjmp(e.jb)) {
        jpeg_create_decompress(&d);
        if ((r = header(&d, mem, len, err, errlen)) > 0) {
            *w = (int)d.image_width;
            *h = (int)d.image_height;
            *nc = r;
            r = 0;
        }
    }
    jpeg_destroy_decompress(&d);
    return r;
}

static int b_read(const void *mem, size_t len, float *px, char *err, size_t errlen)
{
    struct jpeg_decompress_struct d;
    struct err_mgr e;
    unsigned char *volatile row = NULL;
    volatile int r = -1;

    start(&d, &e, err, errlen);
    if (!setjmp(e.jb)) {
        float lut[256];
        jpeg_create_decompress(&d);
        if ((r = header(&d, mem, len, err, errlen)) > 0) {
            int nc = r;
            size_t n = (size_t)d.image_width * nc;
            r = -1;
            for (int v = 0; v < 256; v++)
                lut[v] = (float)v / 255.0f;
            jpeg_start_decompress(&d);
            if (!(row = malloc(n)))
                longjmp(e.jb, 1);
            while (d.output_scanline < d.output_height) {
                float *o = px + (size_t)d.output_scanline * n;
                JSAMPROW rp = row;
                jpeg_read_scanlines(&d, &rp, 1);
                for (size_t i = 0; i < n; i++)
                    o[i] = lut[row[i]];
            }
            jpeg_finish_decompress(&d);
            r = 0;
        }
    } else if (!row && !err[0]) {
        snprintf(err, errlen, "out of memory");
    }
    free(row);
    jpeg_destroy_decompress(&d);
    return r;
}

/* Scanlines asked for TEX_CODEC_BAND at a time and written one by one, as before. */
static int b_write_rows(int fd, int w, int h, int nc, int bits,
                        int (*rows)(void *arg, int y, int n, void *dst), void *arg, char *err,
                        size_t errlen)
{
    struct jpeg_compress_struct c;
    struct err_mgr e;
    int dfd = dup(fd);
    FILE *volatile f = dfd >= 0 ? fdopen(dfd, "wb") : NULL;
    unsigned char *volatile band = NULL;
    volatile int r = -1;

    if (!f || bits != 8 || (nc != 1 && nc != 3) ||
        !(band = malloc((size_t)w * nc * TEX_CODEC_BAND))) {
        snprintf(err, errlen, "%s", !f ? "cannot start the JPEG writer"
                                    : bits != 8 || (nc != 1 && nc != 3) ? "bad JPEG layout"
                                                                        : "out of memory");
        if (!f && dfd >= 0)
            close(dfd);
        if (f)
            fclose(f);
        return -1;
    }
    memset(&c, 0, sizeof c);
    c.err = jpeg_std_error(&e.pub);
    e.pub.error_exit = on_error;
    e.pub.emit_message = on_message;
    e.err = err;
    e.errlen = errlen;
    if (!setjmp(e.jb)) {
        jpeg_create_compress(&c);
        jpeg_stdio_dest(&c, f);
        c.image_width = (JDIMENSION)w;
        c.image_height = (JDIMENSION)h;
        c.input_components = nc;
        c.in_color_space = nc == 1 ? JCS_GRAYSCALE : JCS_RGB;
        jpeg_set_defaults(&c);
        jpeg_set_quality(&c, 95, TRUE);
        for (int i = 0; i < c.num_components; i++)
            c.comp_info[i].h_samp_factor = c.comp_info[i].v_samp_factor = 1;
        jpeg_start_compress(&c, TRUE);
        for (int y = 0; y < h; y += TEX_CODEC_BAND) {
            int n = h - y < TEX_CODEC_BAND ? h - y : TEX_CODEC_BAND;
            if (rows(arg, y, n, band) < 0) {
                snprintf(err, errlen, "rows");
                break;
            }
            for (int k = 0; k < n; k++) {
                JSAMPROW rp = (JSAMPROW)band + (size_t)k * w * nc;
                jpeg_write_scanlines(&c, &rp, 1);
            }
            if (y + n >= h) {
                jpeg_finish_compress(&c);
                r = 0;
            }
        }
    }
    jpeg_destroy_compress(&c);
    free(band);
    if (fclose(f) != 0 && r == 0) {
        snprintf(err, errlen, "write error");
        r = -1;
    }
    return r;
}

static int b_write(int fd, const void *px, int w, int h, int nc, int bits, char *err,
                   size_t errlen)
{
    struct tex_codec_px p = {px, (size_t)w * nc};
    return b_write_rows(fd, w, h, nc, bits, tex_codec_copy_rows, &p, err, errlen);
}

__attribute__((visibility("default"))) const struct tex_codec_bridge tex_jpeg_bridge = {
    TEX_CODEC_BRIDGE_VERSION, b_info, b_read, b_write, b_write_rows};
