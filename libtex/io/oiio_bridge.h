/* oiio_bridge.h - the C interface of textura-oiio.so (private to libtex)
 *
 * The one C++ file of Textura, oiio_bridge.cpp, wraps OpenImageIO behind
 * these functions.  libtex loads it with dlopen the first time a file that
 * is not EXR is read or written; the symbol "tex_oiio_bridge" is a
 * struct tex_oiio_bridge.  The bridge does not link libtex: it reports
 * through err and hands pixels to buffers the caller allocates, so that the
 * caller applies its own size limits first.
 */
#ifndef TEX_OIIO_BRIDGE_H
#define TEX_OIIO_BRIDGE_H

#include <stddef.h>

#define TEX_OIIO_BRIDGE_VERSION 1

struct tex_oiio_in; /* an open input */

struct tex_oiio_bridge {
    int version;
    /* Open path, or the file image mem/len when mem is not NULL (ext names its
     * format, e.g. "png").  Fills the size and the channel count. */
    struct tex_oiio_in *(*open)(const char *path, const void *mem, size_t len, const char *ext,
                                int *w, int *h, int *nc, char *err, size_t errlen);
    /* Read the first min(nc, 4) channels as float into px (w*h*nc floats). */
    int (*read)(struct tex_oiio_in *in, float *px, int nc, char *err, size_t errlen);
    void (*close)(struct tex_oiio_in *in);
    /* Write w*h*nc pixels of type bits (8: uint8, 16: uint16, 32: float) to path,
     * in the format that format_name's extension names. */
    int (*write)(const char *path, const char *format_name, const void *px, int w, int h,
                 int nc, int bits, char *err, size_t errlen);
};

#endif
