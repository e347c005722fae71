/* codec_bridge.h - the C interface of textura-png.so, textura-jpeg.so and
 * textura-tiff.so (private to libtex)
 *
 * Each codec library is wrapped by one small C file (png_bridge.c,
 * jpeg_bridge.c, tiff_bridge.c) built as its own shared object, which
 * libtex loads with dlopen the first time a file of that format is read
 * or written: a tool pays for libpng only when it meets a PNG, and never
 * for OpenImageIO's start-up.  The exported symbol is "tex_png_bridge",
 * "tex_jpeg_bridge" or "tex_tiff_bridge", a struct tex_codec_bridge.
 *
 * Like the OpenImageIO bridge, a codec bridge does not link libtex: it
 * reports one line through err and decodes into a buffer the caller
 * allocated after checking the size that info returned, so the caller's
 * limits apply before any allocation.  Values are kept as stored: integer
 * samples become v / (2^bits - 1), no transfer function is applied (PNG's
 * gAMA, sRGB, iCCP and cHRM chunks are ignored, as netpbm does).
 */
#ifndef TEX_CODEC_BRIDGE_H
#define TEX_CODEC_BRIDGE_H

#include <stddef.h>

#define TEX_CODEC_BRIDGE_VERSION 2

/* What read and info return besides 0 and -1: the bridge does not take this
 * variant of its format (e.g. a CMYK JPEG); the caller may try OpenImageIO. */
#define TEX_CODEC_DECLINED (-2)

struct tex_codec_bridge {
    int version;
    /* The size and channel count of the file image mem/len, from its header; the
     * count may exceed 4 (a TIFF's extra samples). */
    int (*info)(const void *mem, size_t len, int *w, int *h, int *nc, char *err, size_t errlen);
    /* Decode it into px, w*h*min(nc, 4) floats: the first four channels. */
    int (*read)(const void *mem, size_t len, float *px, char *err, size_t errlen);
    /* Encode w*h*nc samples of bits (8: uint8, 16: uint16, 32: float) to fd,
     * which may be a pipe for PNG and JPEG (TIFF needs a file it can seek). */
    int (*write)(int fd, const void *px, int w, int h, int nc, int bits, char *err,
                 size_t errlen);
    /* The same file, its rows asked for as it encodes them, never held whole: rows(arg,
     * y, n, dst) puts rows y..y+n-1 (w*nc samples of bits each, one after the other) at
     * dst, from the top, n at most TEX_CODEC_BAND; 0, or -1 with its own error (err then
     * says "rows").  write is this with rows copied from px: the same bytes. */
    int (*write_rows)(int fd, int w, int h, int nc, int bits,
                      int (*rows)(void *arg, int y, int n, void *dst), void *arg, char *err,
                      size_t errlen);
};
#define TEX_CODEC_BAND 64

/* write's rows from px: a bridge's write calls its write_rows with copy_rows and this. */
struct tex_codec_px {
    const unsigned char *px;
    size_t stride; /* bytes a row */
};
static inline int tex_codec_copy_rows(void *arg, int y, int n, void *dst)
{
    const struct tex_codec_px *p = arg;
    __builtin_memcpy(dst, p->px + p->stride * (size_t)y, p->stride * (size_t)n);
    return 0;
}

#endif
